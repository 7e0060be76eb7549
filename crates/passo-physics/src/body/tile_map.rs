//! Tile maps: a grid of solid cells, each of a kind (its material, or a
//! one-way cell), turned into as few boxes as the level needs.
//!
//! A level drawn on a grid (by hand, as ASCII art, or in the Tiled editor
//! through `passo-scene`) becomes static or kinematic boxes with
//! [`World::add_tile_map`](crate::World::add_tile_map). Cells are merged:
//! first each row's runs of one kind, then runs with the same columns and
//! kind in consecutive rows, so a floor is one box, a wall is one box, and
//! a solid block is one box. Seamless ground makes the joints between the
//! boxes no edges to catch on, however they are merged: a face that
//! neighbouring boxes cover together is never a contact normal.

use crate::PhysicsError;
use crate::body::def::check_one_way;
use crate::constants::{MAX_FRICTION, MAX_SHAPE_SIZE};
use crate::error::{at_most, finite_vec, unit_interval};
use crate::geometry::aabb::Aabb;
use glam::Vec2;

/// Most cells a map may have: 4096 × 4096 (16 MB of cells).
pub const MAX_TILE_CELLS: usize = 4096 * 4096;

/// What one kind of solid cell is made of.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TileKind {
    /// Friction coefficient, in `[0, MAX_FRICTION]`.
    pub friction: f32,
    /// Restitution, in `[0, 1]`.
    pub restitution: f32,
    /// A one-way cell: the outward normal of its solid side (`(0, 1)`: land
    /// on it from above, jump through it from below). `None`: solid.
    pub one_way: Option<Vec2>,
    /// A sloped cell: the part of it that is solid. `None`: the whole cell.
    /// (A one-way cell does not slope.)
    pub slope: Option<Slope>,
}

/// Which part of a sloped cell is solid: below a line across it. The
/// slopes of a map, with the solid cells they touch, become chains (see
/// [`TileMap::chains`]), so walking from a slope onto the flat and back
/// is smooth.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Slope {
    /// 45° rising to the right: solid below the diagonal from the
    /// lower-left corner to the upper-right one (`/`).
    Up,
    /// 45° falling to the right (`\`).
    Down,
    /// The lower half of a 2:1 slope rising to the right, over two cells:
    /// from the lower-left corner to the middle of the right side (`r`).
    UpLow,
    /// The upper half of a 2:1 rising slope: from the middle of the left
    /// side to the upper-right corner (`R`).
    UpHigh,
    /// The upper half of a 2:1 slope falling to the right: from the
    /// upper-left corner to the middle of the right side (`F`).
    DownHigh,
    /// The lower half of a 2:1 falling slope: from the middle of the left
    /// side to the lower-right corner (`f`).
    DownLow,
}

impl Slope {
    /// The solid part's corners, counter-clockwise from the lower-left
    /// corner, in half cells.
    fn outline(self) -> &'static [(i64, i64)] {
        match self {
            Self::Up => &[(0, 0), (2, 0), (2, 2)],
            Self::Down => &[(0, 0), (2, 0), (0, 2)],
            Self::UpLow => &[(0, 0), (2, 0), (2, 1)],
            Self::UpHigh => &[(0, 0), (2, 0), (2, 2), (0, 1)],
            Self::DownHigh => &[(0, 0), (2, 0), (2, 1), (0, 2)],
            Self::DownLow => &[(0, 0), (2, 0), (0, 1)],
        }
    }
}

/// A chain of a tile map (see [`TileMap::chains`]): a closed outline,
/// clockwise (solid inside, on the right of the way it goes).
#[derive(Clone, Debug, PartialEq)]
pub struct TileChain {
    /// The corners, metres, in order; the last joins the first.
    pub points: Vec<Vec2>,
    /// The kind whose material it has (index into [`TileMap::kinds`]).
    pub kind: u8,
}

impl TileKind {
    /// Plain ground: friction 0.6 (the body default), no bounce.
    pub const SOLID: Self = Self {
        friction: crate::constants::DEFAULT_FRICTION,
        restitution: 0.0,
        one_way: None,
        slope: None,
    };
    /// Ice: friction 0.02.
    pub const ICE: Self = Self {
        friction: 0.02,
        ..Self::SOLID
    };
    /// A bouncy cell: restitution 0.9.
    pub const BOUNCY: Self = Self {
        restitution: 0.9,
        ..Self::SOLID
    };
    /// A one-way cell landed on from above.
    pub const ONE_WAY: Self = Self {
        one_way: Some(Vec2::Y),
        ..Self::SOLID
    };

    /// Plain ground sloped as `slope`.
    pub const fn sloped(slope: Slope) -> Self {
        Self {
            slope: Some(slope),
            ..Self::SOLID
        }
    }

    fn validate(&self) -> Result<(), PhysicsError> {
        if self.slope.is_some() && self.one_way.is_some() {
            return Err(PhysicsError::InvalidTileMap(
                "a one-way cell cannot slope".into(),
            ));
        }
        at_most(
            "TileKind::friction",
            self.friction,
            MAX_FRICTION,
            "in [0, 1000]",
        )?;
        unit_interval("TileKind::restitution", self.restitution)?;
        if let Some(n) = self.one_way {
            check_one_way("TileKind::one_way", n)?;
        }
        Ok(())
    }
}

/// The characters of [`TileMap::from_ascii`] and the kinds they make.
pub const ASCII_LEGEND: [(char, Option<TileKind>); 12] = [
    ('#', Some(TileKind::SOLID)),
    ('-', Some(TileKind::ONE_WAY)),
    ('~', Some(TileKind::ICE)),
    ('^', Some(TileKind::BOUNCY)),
    ('/', Some(TileKind::sloped(Slope::Up))),
    ('\\', Some(TileKind::sloped(Slope::Down))),
    ('r', Some(TileKind::sloped(Slope::UpLow))),
    ('R', Some(TileKind::sloped(Slope::UpHigh))),
    ('F', Some(TileKind::sloped(Slope::DownHigh))),
    ('f', Some(TileKind::sloped(Slope::DownLow))),
    ('.', None),
    (' ', None),
];

/// A grid of cells, each empty or solid of one [`TileKind`]. Cell `(0, 0)`
/// is the lower-left one (y up, as everywhere in Passo).
#[derive(Clone, Debug, PartialEq)]
pub struct TileMap {
    origin: Vec2,
    cell_size: Vec2,
    width: u32,
    height: u32,
    /// Per cell, row by row from the bottom: 0 empty, `k` = `kinds[k - 1]`.
    cells: Vec<u8>,
    kinds: Vec<TileKind>,
}

/// One box of a merged map: cells `min..max` (exclusive) of one kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileRect {
    /// The lower-left cell, `(column, row)`.
    pub min: (u32, u32),
    /// One past the upper-right cell.
    pub max: (u32, u32),
    /// Index into [`TileMap::kinds`].
    pub kind: u8,
}

impl TileMap {
    /// An empty map of `width × height` cells of `cell_size` metres whose
    /// lower-left corner is at `origin`.
    ///
    /// # Errors
    /// A size of zero, more than [`MAX_TILE_CELLS`] cells, a cell size not
    /// in `(0, MAX_SHAPE_SIZE]`, or a map reaching beyond `MAX_COORDINATE`.
    pub fn new(
        width: u32,
        height: u32,
        cell_size: Vec2,
        origin: Vec2,
    ) -> Result<Self, PhysicsError> {
        let cells = width as usize * height as usize;
        if cells == 0 || cells > MAX_TILE_CELLS {
            return Err(PhysicsError::OutOfRange {
                what: "TileMap cells (width × height)",
                value: cells as f32,
                allowed: "in [1, 4096 × 4096] (MAX_TILE_CELLS)",
            });
        }
        finite_vec("TileMap::cell_size", cell_size)?;
        let smallest = cell_size.min_element();
        if !(smallest > 0.0 && cell_size.max_element() <= MAX_SHAPE_SIZE) {
            return Err(PhysicsError::OutOfRange {
                what: "TileMap::cell_size",
                value: smallest,
                allowed: "> 0 and at most 1e6 m (MAX_SHAPE_SIZE) along each axis",
            });
        }
        let far = origin + cell_size * Vec2::new(width as f32, height as f32);
        crate::error::position("TileMap::origin", origin)?;
        crate::error::position("TileMap (its far corner)", far)?;
        Ok(Self {
            origin,
            cell_size,
            width,
            height,
            cells: vec![0; cells],
            kinds: Vec::new(),
        })
    }

    /// A map drawn as text, one character per cell and one line per row,
    /// the first line the top row: `#` solid, `-` one-way, `~` ice, `^`
    /// bouncy, `/` and `\` 45° slopes, `r` then `R` a 2:1 slope rising over
    /// two cells, `F` then `f` a 2:1 slope falling over two, `.` or a space
    /// empty ([`ASCII_LEGEND`]). Lines may differ in
    /// length (the rest of a short line is empty); blank lines before the
    /// first and after the last row are ignored.
    ///
    /// ```
    /// use passo_physics::{TileMap, glam::Vec2};
    /// let map = TileMap::from_ascii("
    ///     #......#
    ///     #..--..#
    ///     ########", Vec2::splat(0.5), Vec2::ZERO).unwrap();
    /// // The floor, the two walls and the one-way ledge.
    /// assert_eq!(map.rects().len(), 4);
    /// ```
    ///
    /// Leading spaces common to every row are removed, so a map can be
    /// indented in source code.
    ///
    /// # Errors
    /// A character not in the legend (naming its line and column), or the
    /// errors of [`TileMap::new`].
    pub fn from_ascii(text: &str, cell_size: Vec2, origin: Vec2) -> Result<Self, PhysicsError> {
        // The rows between the first and the last line that is not blank,
        // measured without copying the text, so that a map too large is an
        // error before anything the size of the text is allocated.
        let blank = |l: &str| l.trim().is_empty();
        let first = text.lines().position(|l| !blank(l)).unwrap_or(0);
        let height = text
            .lines()
            .skip(first)
            .enumerate()
            .filter(|(_, l)| !blank(l))
            .last()
            .map_or(0, |(i, _)| i + 1);
        let lines = || text.lines().skip(first).take(height);
        let indent = lines()
            .filter(|l| !blank(l))
            .map(|l| l.len() - l.trim_start_matches(' ').len())
            .min()
            .unwrap_or(0);
        let width = lines()
            .map(|l| l.chars().count().saturating_sub(indent))
            .max()
            .unwrap_or(0);
        let too_big = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        let mut map = Self::new(too_big(width), too_big(height), cell_size, origin)?;
        let mut kind_of = [None; ASCII_LEGEND.len()];
        for (line, row) in lines().enumerate() {
            let y = (height - 1 - line) as u32;
            for (column, c) in row.chars().skip(indent).enumerate() {
                let Some(entry) = ASCII_LEGEND.iter().position(|(ch, _)| *ch == c) else {
                    return Err(PhysicsError::InvalidTileMap(format!(
                        "line {}, column {}: {c:?} is not a tile (use # solid, - one-way, ~ ice, ^ bouncy, / \\ r R F f slopes, . or space empty)",
                        line + 1,
                        column + indent + 1
                    )));
                };
                let Some(kind) = ASCII_LEGEND[entry].1 else {
                    continue;
                };
                let k = match kind_of[entry] {
                    Some(k) => k,
                    None => {
                        let k = map.add_kind(kind)?;
                        kind_of[entry] = Some(k);
                        k
                    }
                };
                map.set(column as u32, y, Some(k))?;
            }
        }
        Ok(map)
    }

    /// Adds a kind of cell and returns its index for [`set`](Self::set).
    ///
    /// # Errors
    /// A friction, restitution or one-way normal out of range, or more than
    /// 255 kinds.
    pub fn add_kind(&mut self, kind: TileKind) -> Result<u8, PhysicsError> {
        kind.validate()?;
        if self.kinds.len() >= 255 {
            return Err(PhysicsError::InvalidTileMap(
                "more than 255 kinds of cell".into(),
            ));
        }
        self.kinds.push(kind);
        Ok((self.kinds.len() - 1) as u8)
    }

    /// Makes cell `(x, y)` empty (`None`) or solid of kind `kind`.
    ///
    /// # Errors
    /// A cell outside the map, or a kind that was never added.
    pub fn set(&mut self, x: u32, y: u32, kind: Option<u8>) -> Result<(), PhysicsError> {
        let i = self.index(x, y).ok_or_else(|| {
            PhysicsError::InvalidTileMap(format!(
                "cell ({x}, {y}) is outside the {} × {} map",
                self.width, self.height
            ))
        })?;
        if let Some(k) = kind
            && usize::from(k) >= self.kinds.len()
        {
            return Err(PhysicsError::InvalidTileMap(format!(
                "kind {k} was never added (the map has {})",
                self.kinds.len()
            )));
        }
        self.cells[i] = kind.map_or(0, |k| k + 1);
        Ok(())
    }

    /// The kind of cell `(x, y)`, or `None` if it is empty or outside.
    pub fn get(&self, x: u32, y: u32) -> Option<u8> {
        let cell = self.cells[self.index(x, y)?];
        cell.checked_sub(1)
    }

    /// The cell holding `point`, or `None` outside the map.
    pub fn cell_at(&self, point: Vec2) -> Option<(u32, u32)> {
        let p = ((point - self.origin) / self.cell_size).floor();
        let inside =
            p.x >= 0.0 && p.y >= 0.0 && p.x < self.width as f32 && p.y < self.height as f32;
        inside.then_some((p.x as u32, p.y as u32))
    }

    /// Width in cells.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in cells.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Width and height of a cell, metres.
    pub fn cell_size(&self) -> Vec2 {
        self.cell_size
    }

    /// The lower-left corner of cell `(0, 0)`, metres.
    pub fn origin(&self) -> Vec2 {
        self.origin
    }

    /// The kinds of cell, by index.
    pub fn kinds(&self) -> &[TileKind] {
        &self.kinds
    }

    /// The world box of cells `rect`.
    pub fn rect_aabb(&self, rect: &TileRect) -> Aabb {
        let corner =
            |(x, y): (u32, u32)| self.origin + self.cell_size * Vec2::new(x as f32, y as f32);
        Aabb {
            min: corner(rect.min),
            max: corner(rect.max),
        }
    }

    /// The solid cells merged into rectangles, bottom row first: each
    /// row's runs of one kind, joined with the runs of the same columns
    /// and kind in the rows above. The same map always gives the same
    /// rectangles in the same order.
    pub fn rects(&self) -> Vec<TileRect> {
        // Cells that are part of a chain are left out.
        let chained = self.chain_cells();
        let cell_at = |i: usize| {
            if chained.as_ref().is_some_and(|c| c[i] != 0) {
                0
            } else {
                self.cells[i]
            }
        };
        let mut done = Vec::new();
        // Rectangles still growing upwards, in column order.
        let mut open: Vec<TileRect> = Vec::new();
        let mut next: Vec<TileRect> = Vec::new();
        for y in 0..self.height {
            let first = (y * self.width) as usize;
            let span = first..first + self.width as usize;
            let row: std::borrow::Cow<'_, [u8]> = match &chained {
                None => std::borrow::Cow::Borrowed(&self.cells[span]),
                Some(_) => std::borrow::Cow::Owned(span.map(cell_at).collect()),
            };
            let mut j = 0;
            let mut x = 0;
            while x < self.width {
                let cell = row[x as usize];
                if cell == 0 {
                    x += 1;
                    continue;
                }
                let start = x;
                while x < self.width && row[x as usize] == cell {
                    x += 1;
                }
                let kind = cell - 1;
                // Close the open rectangles that start before this run.
                while j < open.len() && open[j].min.0 < start {
                    done.push(open[j]);
                    j += 1;
                }
                let same = open
                    .get(j)
                    .is_some_and(|r| r.min.0 == start && r.max.0 == x && r.kind == kind);
                if same {
                    let mut r = open[j];
                    r.max.1 = y + 1;
                    next.push(r);
                    j += 1;
                } else {
                    next.push(TileRect {
                        min: (start, y),
                        max: (x, y + 1),
                        kind,
                    });
                }
            }
            done.extend_from_slice(&open[j..]);
            std::mem::swap(&mut open, &mut next);
            next.clear();
        }
        done.extend_from_slice(&open);
        done
    }

    fn index(&self, x: u32, y: u32) -> Option<usize> {
        (x < self.width && y < self.height).then(|| (y * self.width + x) as usize)
    }

    /// Per cell, the chain it is part of: 0 for none, else 1 + the kind
    /// whose material the chain has. A chain is made of the sloped cells
    /// and the solid cells joined to them by a side through cells of the
    /// same material (not one-way). `None` for a map with no slope.
    fn chain_cells(&self) -> Option<Vec<u8>> {
        if self.kinds.iter().all(|k| k.slope.is_none()) {
            return None;
        }
        let same = |a: &TileKind, b: &TileKind| {
            a.friction == b.friction && a.restitution == b.restitution && b.one_way.is_none()
        };
        let width = self.width as usize;
        let mut region = vec![0u8; self.cells.len()];
        let mut stack = Vec::new();
        for seed in 0..self.cells.len() {
            let Some(k) = self.cells[seed].checked_sub(1) else {
                continue;
            };
            let kind = self.kinds[usize::from(k)];
            if kind.slope.is_none() || region[seed] != 0 {
                continue;
            }
            region[seed] = k + 1;
            stack.push(seed);
            while let Some(i) = stack.pop() {
                let (x, y) = ((i % width) as u32, (i / width) as u32);
                let sides = [
                    x.checked_sub(1).map(|x| (x, y)),
                    Some((x + 1, y)),
                    y.checked_sub(1).map(|y| (x, y)),
                    Some((x, y + 1)),
                ];
                for (nx, ny) in sides.into_iter().flatten() {
                    let Some(j) = self.index(nx, ny) else {
                        continue;
                    };
                    if region[j] != 0 {
                        continue;
                    }
                    if let Some(m) = self.cells[j].checked_sub(1)
                        && same(&kind, &self.kinds[usize::from(m)])
                    {
                        region[j] = k + 1;
                        stack.push(j);
                    }
                }
            }
        }
        Some(region)
    }

    /// The map's chains: the outlines of its sloped cells together with the
    /// solid cells of the same material they touch by a side (see
    /// [`Slope`]), each a closed loop going clockwise, with corners only
    /// where the outline turns. [`rects`](Self::rects) leaves their cells
    /// out, and [`World::add_tile_map`](crate::World::add_tile_map) adds
    /// them as chains ([`World::add_chain`](crate::World::add_chain)): a
    /// slope meets the flat beside it as smoothly as a chain's segments
    /// meet. Empty for a map with no slope. The same map always gives the
    /// same chains in the same order.
    ///
    /// ```
    /// use passo_physics::{TileMap, glam::Vec2};
    /// // Flat, a 45° slope up, flat on top: one outline of the cells,
    /// // clockwise from the top of the flat at the left.
    /// let map = TileMap::from_ascii("..####\n./####\n######", Vec2::ONE, Vec2::ZERO).unwrap();
    /// let chains = map.chains();
    /// assert_eq!(chains.len(), 1);
    /// assert_eq!(chains[0].points, [
    ///     Vec2::new(0.0, 1.0), Vec2::new(1.0, 1.0), Vec2::new(2.0, 2.0), Vec2::new(2.0, 3.0),
    ///     Vec2::new(6.0, 3.0), Vec2::new(6.0, 0.0), Vec2::new(0.0, 0.0),
    /// ]);
    /// assert!(map.rects().is_empty());
    /// ```
    pub fn chains(&self) -> Vec<TileChain> {
        let Some(region) = self.chain_cells() else {
            return Vec::new();
        };
        let width = self.width as usize;
        // Every chained cell's outline as edges in half cells, counter-
        // clockwise: an edge two cells share appears once each way.
        const SQUARE: [(i64, i64); 4] = [(0, 0), (2, 0), (2, 2), (0, 2)];
        type Edge = (u8, (i64, i64), (i64, i64));
        let mut edges: Vec<Edge> = Vec::new();
        for (i, &r) in region.iter().enumerate() {
            if r == 0 {
                continue;
            }
            let (x, y) = ((i % width) as i64, (i / width) as i64);
            let k = usize::from(self.cells[i] - 1);
            let outline: &[(i64, i64)] = match self.kinds[k].slope {
                Some(slope) => slope.outline(),
                None => &SQUARE,
            };
            for (n, &(ax, ay)) in outline.iter().enumerate() {
                let (bx, by) = outline[(n + 1) % outline.len()];
                edges.push((r, (2 * x + ax, 2 * y + ay), (2 * x + bx, 2 * y + by)));
            }
        }
        edges.sort_unstable();
        // The edges whose reverse is not there: the outline.
        let outline: Vec<Edge> = edges
            .iter()
            .filter(|&&(r, a, b)| edges.binary_search(&(r, b, a)).is_err())
            .copied()
            .collect();
        let mut used = vec![false; outline.len()];
        let mut chains = Vec::new();
        for first in 0..outline.len() {
            if used[first] {
                continue;
            }
            let (r, start, _) = outline[first];
            let mut corners: Vec<(i64, i64)> = Vec::new();
            let mut at = first;
            loop {
                used[at] = true;
                let (_, a, b) = outline[at];
                corners.push(a);
                if b == start {
                    break;
                }
                // The unused edges from `b`; where two pieces meet at a
                // point, the one turning left keeps the loop around one.
                let from = outline.partition_point(|&(q, p, _)| (q, p) < (r, b));
                let left = |e: usize| {
                    let c = outline[e].2;
                    let (d0, d1) = ((b.0 - a.0, b.1 - a.1), (c.0 - b.0, c.1 - b.1));
                    (d0.0 * d1.1 - d0.1 * d1.0).signum()
                };
                let next = (from..outline.len())
                    .take_while(|&e| (outline[e].0, outline[e].1) == (r, b))
                    .filter(|&e| !used[e])
                    .max_by_key(|&e| (left(e), std::cmp::Reverse(e)));
                match next {
                    Some(e) => at = e,
                    None => break,
                }
            }
            // Corners only where the outline turns.
            let n = corners.len();
            let turns = (0..n).filter(|&i| {
                let (p, q, s) = (corners[(i + n - 1) % n], corners[i], corners[(i + 1) % n]);
                (q.0 - p.0) * (s.1 - q.1) - (q.1 - p.1) * (s.0 - q.0) != 0
            });
            let mut points: Vec<Vec2> = turns
                .map(|i| {
                    let (x, y) = corners[i];
                    self.origin + self.cell_size * Vec2::new(x as f32, y as f32) * 0.5
                })
                .collect();
            // Clockwise: solid on the right of the way it goes.
            points.reverse();
            chains.push(TileChain {
                points,
                kind: r - 1,
            });
        }
        chains
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_blank_lines_around_a_map_are_dropped_in_one_pass() {
        // A million blank lines before and after (removing them one by one
        // from the front of a list took minutes).
        let blank = "\n".repeat(1_000_000);
        let text = format!("{blank}  #.\n\n   -{blank}");
        let map = TileMap::from_ascii(&text, Vec2::ONE, Vec2::ZERO).unwrap();
        assert_eq!((map.width(), map.height()), (2, 3));
        assert!(map.get(0, 2).is_some() && map.get(1, 2).is_none());
        assert!(map.get(0, 1).is_none() && map.get(1, 0).is_some());
        // Lines are counted from the first row that is not blank, columns
        // from the start of the line.
        let err = TileMap::from_ascii(&format!("{blank}  #.\n   x"), Vec2::ONE, Vec2::ZERO)
            .unwrap_err()
            .to_string();
        assert!(err.contains("line 2, column 4"), "{err}");
        // A map too wide is refused before its rows are read.
        let wide = ".".repeat(MAX_TILE_CELLS) + "#";
        assert!(TileMap::from_ascii(&wide, Vec2::ONE, Vec2::ZERO).is_err());
        assert!(TileMap::from_ascii(&blank, Vec2::ONE, Vec2::ZERO).is_err());
    }

    #[test]
    fn ascii_rows_run_top_down_and_cells_merge_into_few_rects() {
        let map = TileMap::from_ascii(
            "
            #......#
            #..--..#
            #~~~####
            ########",
            Vec2::splat(0.5),
            Vec2::new(-2.0, 0.0),
        )
        .unwrap();
        assert_eq!((map.width(), map.height()), (8, 4));
        // The top-left cell is solid, the one beside it empty.
        assert!(map.get(0, 3).is_some() && map.get(1, 3).is_none());
        let ice = map.get(1, 1).unwrap();
        assert_eq!(map.kinds()[ice as usize], TileKind::ICE);
        let rects = map.rects();
        // Floor; ice run and the solid run beside it (one row); the two
        // walls above; the one-way ledge.
        let count = |kind: TileKind| {
            rects
                .iter()
                .filter(|r| map.kinds()[r.kind as usize] == kind)
                .count()
        };
        assert_eq!(count(TileKind::ONE_WAY), 1);
        assert_eq!(count(TileKind::ICE), 1);
        assert_eq!(rects.len(), 6, "{rects:?}");
        // Every solid cell is in exactly one rect, and no empty one.
        for y in 0..map.height() {
            for x in 0..map.width() {
                let inside = rects
                    .iter()
                    .filter(|r| (r.min.0..r.max.0).contains(&x) && (r.min.1..r.max.1).contains(&y))
                    .count();
                assert_eq!(
                    inside,
                    usize::from(map.get(x, y).is_some()),
                    "cell ({x}, {y})"
                );
            }
        }
        let floor = rects.iter().find(|r| r.min == (0, 0)).unwrap();
        assert_eq!(floor.max, (8, 1));
        let aabb = map.rect_aabb(floor);
        assert_eq!(
            (aabb.min, aabb.max),
            (Vec2::new(-2.0, 0.0), Vec2::new(2.0, 0.5))
        );
    }

    #[test]
    fn a_solid_block_is_one_rect_and_a_checkerboard_one_per_cell() {
        let mut map = TileMap::new(100, 50, Vec2::ONE, Vec2::ZERO).unwrap();
        let solid = map.add_kind(TileKind::SOLID).unwrap();
        for y in 0..50 {
            for x in 0..100 {
                map.set(x, y, Some(solid)).unwrap();
            }
        }
        assert_eq!(map.rects().len(), 1);
        for y in 0..50 {
            for x in 0..100 {
                map.set(x, y, ((x + y) % 2 == 0).then_some(solid)).unwrap();
            }
        }
        assert_eq!(map.rects().len(), 2_500);
    }

    #[test]
    fn bad_maps_are_refused_with_the_reason() {
        let err = TileMap::from_ascii("#x#", Vec2::ONE, Vec2::ZERO).unwrap_err();
        assert!(err.to_string().contains("line 1, column 2"), "{err}");
        assert!(TileMap::new(0, 5, Vec2::ONE, Vec2::ZERO).is_err());
        assert!(TileMap::new(5000, 5000, Vec2::ONE, Vec2::ZERO).is_err());
        assert!(TileMap::new(5, 5, Vec2::new(1.0, 0.0), Vec2::ZERO).is_err());
        assert!(TileMap::new(5, 5, Vec2::ONE, Vec2::new(f32::NAN, 0.0)).is_err());
        assert!(
            TileMap::new(1000, 1000, Vec2::splat(1e5), Vec2::ZERO).is_err(),
            "beyond 1e7 m"
        );
        let mut map = TileMap::new(2, 2, Vec2::ONE, Vec2::ZERO).unwrap();
        assert!(map.set(2, 0, None).is_err());
        assert!(map.set(0, 0, Some(0)).is_err(), "no kind added yet");
        let bad = TileKind {
            friction: f32::NAN,
            ..TileKind::SOLID
        };
        assert!(map.add_kind(bad).is_err());
        assert_eq!(map.cell_at(Vec2::new(1.5, 0.5)), Some((1, 0)));
        assert_eq!(map.cell_at(Vec2::new(-0.5, 0.5)), None);
    }

    #[test]
    fn slopes_and_the_ground_they_touch_become_one_outline_and_no_rects() {
        // A hill: 45° up, flat, 2:1 down over two cells; ice beside it and
        // a one-way ledge above stay boxes.
        let map = TileMap::from_ascii(
            "
            ....--....
            ../###Ff..
            ##########~~",
            Vec2::ONE,
            Vec2::ZERO,
        )
        .unwrap();
        let chains = map.chains();
        assert_eq!(chains.len(), 1);
        let expected = [
            (0.0, 1.0),
            (2.0, 1.0),
            (3.0, 2.0),
            (6.0, 2.0),
            (8.0, 1.0),
            (10.0, 1.0),
            (10.0, 0.0),
            (0.0, 0.0),
        ];
        let points: Vec<(f32, f32)> = chains[0].points.iter().map(|p| (p.x, p.y)).collect();
        // The same loop, from wherever it starts.
        let start = points.iter().position(|&p| p == expected[0]).unwrap();
        let turned: Vec<_> = points[start..]
            .iter()
            .chain(&points[..start])
            .copied()
            .collect();
        assert_eq!(turned, expected);
        let rects = map.rects();
        let kinds: Vec<TileKind> = rects.iter().map(|r| map.kinds()[r.kind as usize]).collect();
        assert_eq!(kinds, [TileKind::ICE, TileKind::ONE_WAY]);
        // Without a slope the same map is boxes alone, as before.
        let flat = TileMap::from_ascii(
            "....--....\n..######..\n##########~~",
            Vec2::ONE,
            Vec2::ZERO,
        )
        .unwrap();
        assert!(flat.chains().is_empty());
        assert_eq!(flat.rects().len(), 4);
    }

    #[test]
    fn every_sloped_cell_s_solid_part_is_inside_its_chain() {
        // Each slope alone on a floor: the outline's area is the floor's
        // plus the slope's solid part (shoelace formula, clockwise).
        for (c, part) in [
            ('/', 0.5f32),
            ('\\', 0.5),
            ('r', 0.25),
            ('R', 0.75),
            ('F', 0.75),
            ('f', 0.25),
        ] {
            let text = format!(".{c}.\n###");
            let map = TileMap::from_ascii(&text, Vec2::ONE, Vec2::ZERO).unwrap();
            let chains = map.chains();
            assert_eq!(chains.len(), 1, "{c}");
            let p = &chains[0].points;
            let twice: f32 = (0..p.len())
                .map(|i| p[i].perp_dot(p[(i + 1) % p.len()]))
                .sum();
            assert!((-0.5 * twice - (3.0 + part)).abs() < 1e-6, "{c}: {p:?}");
        }
        // Two pieces meeting at one corner are two loops.
        let map = TileMap::from_ascii("./\n/.", Vec2::ONE, Vec2::ZERO).unwrap();
        assert_eq!(map.chains().len(), 2);
    }
}
