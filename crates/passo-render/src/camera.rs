//! A 2D camera: world metres, y up, zoom and pan.

use glam::Vec2;

/// What part of the world a picture shows: the point at its centre and how
/// many metres it spans vertically (the width follows the viewport's
/// aspect ratio, so circles stay round).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera2D {
    /// World point at the centre of the picture, metres.
    pub centre: Vec2,
    /// Height of the visible region, metres (> 0).
    pub height: f32,
}

impl Camera2D {
    /// Whether the camera shows something: a finite centre and a finite
    /// height > 0. (Its fields are public; the renderer draws only the
    /// background through a camera that is not.)
    pub fn is_usable(&self) -> bool {
        self.centre.is_finite() && self.height.is_finite() && self.height > 0.0
    }
}

impl Default for Camera2D {
    /// Centred on the origin, 20 m tall.
    fn default() -> Self {
        Self {
            centre: Vec2::ZERO,
            height: 20.0,
        }
    }
}

impl Camera2D {
    /// The camera that shows the box `min..max` whole in a viewport of
    /// `(width, height)` pixels, centred, touching two opposite edges.
    pub fn fit(min: Vec2, max: Vec2, viewport: (u32, u32)) -> Self {
        let size = (max - min).max(Vec2::splat(1e-6));
        let aspect = aspect(viewport);
        Self {
            centre: (min + max) * 0.5,
            height: size.y.max(size.x / aspect),
        }
    }

    /// Metres per pixel in a viewport of this many pixels.
    pub fn pixel_size(&self, viewport: (u32, u32)) -> f32 {
        self.height / viewport.1.max(1) as f32
    }

    /// The visible region, `(min, max)` in metres.
    pub fn bounds(&self, viewport: (u32, u32)) -> (Vec2, Vec2) {
        let half = Vec2::new(self.height * aspect(viewport), self.height) * 0.5;
        (self.centre - half, self.centre + half)
    }

    /// Zooms by `factor` (> 1 zooms in) keeping the world point `anchor`
    /// where it is on screen (the point under the mouse cursor). A factor
    /// not finite and > 0 changes nothing; an anchor not finite zooms about
    /// the centre. Zooming stops at a view 1 mm or 10 000 km high, and
    /// never turns round: a view already beyond either (from `fit`) stays
    /// as it is rather than jump to the limit the other way.
    pub fn zoom_about(&mut self, factor: f32, anchor: Vec2) {
        if !(factor.is_finite() && factor > 0.0) {
            return;
        }
        let anchor = if anchor.is_finite() {
            anchor
        } else {
            self.centre
        };
        let (lowest, highest) = (self.height.min(1e-3), self.height.max(1e7));
        let height = (self.height / factor).clamp(lowest, highest);
        let applied = self.height / height;
        let centre = anchor + (self.centre - anchor) / applied;
        // An anchor near the end of `f32` can overflow the new centre: the
        // view then stays where it was (a centre of -inf never came back).
        if centre.is_finite() {
            self.centre = centre;
            self.height = height;
        }
    }

    /// Moves the view by `delta` metres (not past the end of `f32`).
    pub fn pan(&mut self, delta: Vec2) {
        let centre = self.centre + delta;
        if centre.is_finite() {
            self.centre = centre;
        }
    }

    /// Pixel coordinates (origin top left, y down) of a world point.
    pub fn world_to_pixel(&self, p: Vec2, viewport: (u32, u32)) -> Vec2 {
        let s = self.pixel_size(viewport);
        let half = Vec2::new(viewport.0 as f32, viewport.1 as f32) * 0.5;
        let d = (p - self.centre) / s;
        Vec2::new(half.x + d.x, half.y - d.y)
    }

    /// The world point at pixel coordinates (origin top left, y down).
    pub fn pixel_to_world(&self, px: Vec2, viewport: (u32, u32)) -> Vec2 {
        let s = self.pixel_size(viewport);
        let half = Vec2::new(viewport.0 as f32, viewport.1 as f32) * 0.5;
        self.centre + Vec2::new(px.x - half.x, half.y - px.y) * s
    }

    /// `(centre, scale)` with `clip = (world - centre) * scale`.
    pub(crate) fn clip_transform(&self, viewport: (u32, u32)) -> (Vec2, Vec2) {
        let width = self.height * aspect(viewport);
        (self.centre, Vec2::new(2.0 / width, 2.0 / self.height))
    }
}

fn aspect(viewport: (u32, u32)) -> f32 {
    viewport.0.max(1) as f32 / viewport.1.max(1) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_shows_the_whole_box_with_round_circles() {
        // A 20 x 10 m box in a square viewport: width decides, 20 m tall.
        let cam = Camera2D::fit(Vec2::new(-10.0, 0.0), Vec2::new(10.0, 10.0), (400, 400));
        assert_eq!(cam.centre, Vec2::new(0.0, 5.0));
        assert_eq!(cam.height, 20.0);
        let (min, max) = cam.bounds((400, 400));
        assert!(min.x <= -10.0 && max.x >= 10.0 && min.y <= 0.0 && max.y >= 10.0);
        // A wide viewport: height decides.
        let cam = Camera2D::fit(Vec2::new(-10.0, 0.0), Vec2::new(10.0, 10.0), (800, 200));
        assert_eq!(cam.height, 10.0);
    }

    #[test]
    fn pixels_and_world_points_convert_both_ways() {
        let cam = Camera2D {
            centre: Vec2::new(1.0, 2.0),
            height: 10.0,
        };
        let vp = (200, 100);
        assert_eq!(
            cam.world_to_pixel(Vec2::new(1.0, 2.0), vp),
            Vec2::new(100.0, 50.0)
        );
        // y up in the world is y down in pixels; 10 px per metre.
        assert_eq!(
            cam.world_to_pixel(Vec2::new(2.0, 3.0), vp),
            Vec2::new(110.0, 40.0)
        );
        let p = Vec2::new(-3.25, 4.5);
        assert!((cam.pixel_to_world(cam.world_to_pixel(p, vp), vp) - p).length() < 1e-5);
    }

    #[test]
    fn zoom_keeps_the_anchor_in_place_and_pan_moves() {
        let mut cam = Camera2D::default();
        let vp = (640, 480);
        let anchor = Vec2::new(3.0, -2.0);
        let before = cam.world_to_pixel(anchor, vp);
        cam.zoom_about(2.0, anchor);
        assert_eq!(cam.height, 10.0);
        assert!((cam.world_to_pixel(anchor, vp) - before).length() < 1e-3);
        cam.zoom_about(f32::NAN, anchor);
        cam.zoom_about(0.0, anchor);
        assert_eq!(cam.height, 10.0, "bad factors are ignored");
        cam.pan(Vec2::new(1.0, 0.0));
        assert!((cam.centre.x - (1.5 + 1.0)).abs() < 1e-5);
        // Zooming out about a point near the end of `f32`, or panning past
        // it, would leave an infinite centre no pan brings back.
        let kept = cam;
        cam.zoom_about(1e-6, Vec2::splat(3e38));
        cam.pan(Vec2::splat(f32::MAX));
        cam.pan(Vec2::splat(f32::MAX));
        assert!(cam.centre.is_finite(), "{cam:?}");
        cam.pan(-cam.centre);
        cam.pan(kept.centre);
        assert_eq!(cam.centre, kept.centre, "and a pan brings it back");
    }

    #[test]
    fn zoom_stops_at_its_limits_and_never_turns_round() {
        let vp = (800, 600);
        for factor in [0.5, 2.0] {
            let mut cam = Camera2D::default();
            for _ in 0..200 {
                cam.zoom_about(factor, Vec2::ZERO);
            }
            assert_eq!(cam.height, if factor > 1.0 { 1e-3 } else { 1e7 });
        }
        // A view fitted beyond the limits: zooming out of a 1.5e8 m view
        // used to zoom in 15x (to 1e7), zooming into a 1 µm one out 1000x.
        let mut huge = Camera2D::fit(Vec2::new(-1e8, -1.0), Vec2::new(1e8, 1.0), vp);
        let before = huge.height;
        assert!(before > 1e8);
        huge.zoom_about(0.5, Vec2::ZERO);
        assert_eq!(huge.height, before, "out: no further");
        huge.zoom_about(2.0, Vec2::ZERO);
        assert_eq!(huge.height, before / 2.0, "in: as asked");
        let p = Vec2::new(1.0, 1.0);
        let mut tiny = Camera2D::fit(p, p, vp);
        let before = tiny.height;
        assert!(before < 1e-3);
        tiny.zoom_about(1.1, p);
        assert_eq!(tiny.height, before, "in: no further");
        tiny.zoom_about(0.5, p);
        assert_eq!(tiny.height, before * 2.0, "out: as asked");
    }
}
