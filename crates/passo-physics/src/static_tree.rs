//! A bounding-volume tree over static bodies, built once and rebuilt only
//! when a static body is added, removed or moved.

use crate::Aabb;

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
    pub(crate) fn query(&self, aabb: &Aabb, mut f: impl FnMut(u32)) {
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
                    if self.boxes[item as usize].overlaps(aabb) {
                        f(item);
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

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
        let empty = StaticTree::build(Vec::new());
        empty.query(&Aabb::from_centre(Vec2::ZERO, Vec2::ONE), |_| {
            panic!("no items")
        });
    }
}
