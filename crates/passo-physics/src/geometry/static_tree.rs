//! A bounding-volume tree of boxes, built in one go: over static bodies
//! (rebuilt only when a static body is added, removed or moved), over
//! sleeping bodies, and for queries.

use crate::Aabb;
use glam::Vec2;

const LEAF_SIZE: usize = 4;

#[derive(Clone, Copy, Debug)]
struct Node {
    aabb: Aabb,
    /// Leaf: `items[first..first + count]`. Inner: children at `first` and `first + 1`.
    first: u32,
    count: u32,
}

/// Static bodies' boxes in a binary tree split at the median of the longer
/// axis; queries visit `O(log n + k)` nodes.
#[derive(Clone, Debug, Default)]
pub(crate) struct StaticTree {
    nodes: Vec<Node>,
    items: Vec<u32>,
    boxes: Vec<Aabb>,
}

impl StaticTree {
    /// Builds the tree over `boxes` (the item number is the index).
    pub(crate) fn build(boxes: Vec<Aabb>) -> Self {
        let mut tree = Self::default();
        tree.rebuild(boxes);
        tree
    }

    /// Builds the tree again over `boxes`, reusing its buffers (no
    /// allocation once they have grown).
    pub(crate) fn rebuild(&mut self, boxes: impl IntoIterator<Item = Aabb>) {
        self.boxes.clear();
        self.boxes.extend(boxes);
        self.items.clear();
        self.items.extend(0..self.boxes.len() as u32);
        self.nodes.clear();
        if !self.items.is_empty() {
            self.nodes.push(Node {
                aabb: self.boxes[0],
                first: 0,
                count: 0,
            });
            self.split(0, 0, self.items.len());
        }
    }

    /// Makes room for a tree of `n` items, so rebuilding one no larger
    /// allocates nothing.
    pub(crate) fn reserve(&mut self, n: usize) {
        let more = |len: usize, want: usize| want.saturating_sub(len);
        self.boxes.reserve(more(self.boxes.len(), n));
        self.items.reserve(more(self.items.len(), n));
        // A binary tree with leaves of at least one item has < 2n nodes.
        self.nodes.reserve(more(self.nodes.len(), 2 * n));
    }

    /// The box around every item (`None` for an empty tree).
    pub(crate) fn bounds(&self) -> Option<Aabb> {
        self.nodes.first().map(|n| n.aabb)
    }

    /// The box of item `item`.
    pub(crate) fn item_box(&self, item: u32) -> Aabb {
        self.boxes[item as usize]
    }

    /// Number of items.
    pub(crate) fn len(&self) -> usize {
        self.items.len()
    }

    fn split(&mut self, node: usize, start: usize, end: usize) {
        let items = &mut self.items[start..end];
        let boxes = &self.boxes;
        let bounds = items
            .iter()
            .map(|&i| boxes[i as usize])
            .reduce(|a, b| a.union(&b))
            .expect("a node has items");
        self.nodes[node].aabb = bounds;
        if items.len() <= LEAF_SIZE {
            self.nodes[node].first = start as u32;
            self.nodes[node].count = items.len() as u32;
            return;
        }
        let axis = usize::from(bounds.size().y > bounds.size().x);
        // Median split by centre; ties broken by item number for determinism.
        let mid = items.len() / 2;
        items.select_nth_unstable_by(mid, |&a, &b| {
            let ca = boxes[a as usize].centre()[axis];
            let cb = boxes[b as usize].centre()[axis];
            ca.total_cmp(&cb).then(a.cmp(&b))
        });
        let left = self.nodes.len();
        let placeholder = Node {
            aabb: bounds,
            first: 0,
            count: 0,
        };
        self.nodes.push(placeholder);
        self.nodes.push(placeholder);
        self.nodes[node].first = left as u32;
        self.split(left, start, start + mid);
        self.split(left + 1, start + mid, end);
    }

    /// Calls `f` with every item whose box overlaps `aabb`, in tree order.
    #[inline(always)]
    pub(crate) fn query(&self, aabb: &Aabb, mut f: impl FnMut(u32)) {
        self.query_while(aabb, |item| {
            f(item);
            true
        });
    }

    /// [`query`](Self::query) that stops as soon as `f` returns `false`.
    #[inline(always)]
    pub(crate) fn query_while(&self, aabb: &Aabb, mut f: impl FnMut(u32) -> bool) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if !node.aabb.overlaps(aabb) {
                continue;
            }
            if node.count > 0 {
                for &item in &self.items[node.first as usize..(node.first + node.count) as usize] {
                    if self.boxes[item as usize].overlaps(aabb) && !f(item) {
                        return;
                    }
                }
            } else {
                // The depth is at most log2(n / LEAF_SIZE) + 1 < 64.
                stack[top] = node.first;
                stack[top + 1] = node.first + 1;
                top += 2;
            }
        }
    }

    /// Calls `f` with every item whose box the segment from `origin` along
    /// `dir` up to `max_t` crosses (`t` in units of `dir`), nearer nodes
    /// first. `f` returns a shorter `max_t` once it found a hit, so farther
    /// nodes are skipped.
    pub(crate) fn ray(
        &self,
        origin: Vec2,
        dir: Vec2,
        mut max_t: f32,
        mut f: impl FnMut(u32) -> Option<f32>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let inv = dir.recip();
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if slab_entry(&node.aabb, origin, inv).is_none_or(|t| t > max_t) {
                continue;
            }
            if node.count > 0 {
                for &item in &self.items[node.first as usize..(node.first + node.count) as usize] {
                    let enters = slab_entry(&self.boxes[item as usize], origin, inv);
                    if enters.is_some_and(|t| t <= max_t)
                        && let Some(t) = f(item)
                    {
                        max_t = max_t.min(t);
                    }
                }
            } else {
                // Push the farther child first, so the nearer is visited first.
                let (a, b) = (node.first, node.first + 1);
                let entry = |n: u32| {
                    slab_entry(&self.nodes[n as usize].aabb, origin, inv).unwrap_or(f32::INFINITY)
                };
                let (near, far) = if entry(a) <= entry(b) { (a, b) } else { (b, a) };
                stack[top] = far;
                stack[top + 1] = near;
                top += 2;
            }
        }
    }
}

/// Where the ray `origin + t dir` (with `inv = 1 / dir` per component)
/// enters `aabb`, `t >= 0`, or `None` if it misses (the slab method; a
/// zero component gives an infinite `inv`, and that slab is then all or
/// nothing).
fn slab_entry(aabb: &Aabb, origin: Vec2, inv: Vec2) -> Option<f32> {
    let mut t0 = 0.0f32;
    let mut t1 = f32::INFINITY;
    for axis in 0..2 {
        let (o, i) = (origin[axis], inv[axis]);
        if i.is_infinite() {
            if o < aabb.min[axis] || o > aabb.max[axis] {
                return None;
            }
            continue;
        }
        let (a, b) = ((aabb.min[axis] - o) * i, (aabb.max[axis] - o) * i);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    (t0 <= t1).then_some(t0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn queries_find_exactly_the_overlapping_boxes() {
        let mut boxes = Vec::new();
        for i in 0..500 {
            let x = (i % 25) as f32 * 3.0 + (i as f32 * 0.37).sin();
            let y = (i / 25) as f32 * 2.0;
            let w = 0.5 + (i % 7) as f32;
            boxes.push(Aabb {
                min: Vec2::new(x, y),
                max: Vec2::new(x + w, y + 0.5),
            });
        }
        let tree = StaticTree::build(boxes.clone());
        for q in 0..100 {
            let c = Vec2::new((q * 7 % 80) as f32, (q * 3 % 40) as f32);
            let query = Aabb::from_centre(c, Vec2::new(2.0, 1.5));
            let mut found = Vec::new();
            tree.query(&query, |i| found.push(i));
            found.sort_unstable();
            let want: Vec<u32> = (0..boxes.len() as u32)
                .filter(|&i| boxes[i as usize].overlaps(&query))
                .collect();
            assert_eq!(found, want);
        }
        // Rays find every box the segment crosses.
        let mut crossings = 0;
        for q in 0..100 {
            let origin = Vec2::new((q * 11 % 70) as f32, (q * 5 % 40) as f32 - 2.0);
            let dir = Vec2::new(((q % 9) as f32 - 4.0) * 0.7, ((q % 5) as f32 - 2.0) * 0.9);
            let max_t = 6.0;
            let mut found = Vec::new();
            tree.ray(origin, dir, max_t, |i| {
                found.push(i);
                None
            });
            found.sort_unstable();
            // Each box the segment clearly crosses is found, and none it
            // clearly misses; within rounding of a touch, either.
            for (i, b) in boxes.iter().enumerate() {
                let overlap = segment_overlap(b, origin, dir, max_t);
                let seen = found.contains(&(i as u32));
                if overlap > 1e-4 {
                    assert!(seen, "ray {q} crosses box {i} over {overlap}");
                    crossings += 1;
                } else if overlap < -1e-4 {
                    assert!(!seen, "ray {q} misses box {i} by {}", -overlap);
                }
            }
            // Brute force over points of the segment finds no box the tree missed.
            for k in 0..=600 {
                let p = origin + dir * (max_t * k as f32 / 600.0);
                for (i, b) in boxes.iter().enumerate() {
                    if b.contains_point(p) {
                        assert!(found.contains(&(i as u32)), "box {i} at {p}");
                    }
                }
            }
        }
        assert!(crossings > 300, "the rays cross boxes: {crossings}");
        let empty = StaticTree::build(Vec::new());
        empty.query(&Aabb::from_centre(Vec2::ZERO, Vec2::ONE), |_| {
            panic!("no items")
        });
    }

    /// How long, in units of `dir`, the segment `origin + t dir` for `t`
    /// in `[0, max_t]` stays in the closed box `b`: positive if it crosses
    /// it, zero if it only touches it, negative if not (by how much it
    /// misses; in metres for a segment parallel to the box's sides).
    /// Liang-Barsky clipping in f64, independent of the tree's slabs.
    fn segment_overlap(b: &Aabb, origin: Vec2, dir: Vec2, max_t: f32) -> f64 {
        let (mut enter, mut leave) = (0.0f64, f64::from(max_t));
        for axis in 0..2 {
            let o = f64::from(origin[axis]);
            let d = f64::from(dir[axis]);
            let (lo, hi) = (f64::from(b.min[axis]), f64::from(b.max[axis]));
            if d == 0.0 {
                // Parallel: within the slab throughout, or never.
                let outside = (lo - o).max(o - hi);
                if outside > 0.0 {
                    return -outside;
                }
                continue;
            }
            let (t_lo, t_hi) = ((lo - o) / d, (hi - o) / d);
            enter = enter.max(t_lo.min(t_hi));
            leave = leave.min(t_lo.max(t_hi));
        }
        leave - enter
    }
}
