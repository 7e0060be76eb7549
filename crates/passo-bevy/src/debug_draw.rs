//! Debug drawing with Bevy's gizmos (feature `debug-draw`): every body's
//! shape, the contact points and normals, and the joints.

use bevy::color::Color;
use bevy::math::Isometry2d;
use bevy::prelude::*;
use passo_physics::{self as passo, Shape};

use crate::PassoWorld;
use crate::convert::to_bevy;

/// Draws the physics world with gizmos every frame (in `PostUpdate`),
/// where the last tick left it. Turn parts on and off with
/// [`PassoDebugDraw`].
pub struct PassoDebugDrawPlugin;

impl Plugin for PassoDebugDrawPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<PassoDebugDraw>()
            .add_systems(PostUpdate, draw);
    }
}

/// What [`PassoDebugDrawPlugin`] draws, and in which colours.
#[derive(Resource, Clone, Debug)]
pub struct PassoDebugDraw {
    /// Draw anything at all.
    pub enabled: bool,
    /// Dynamic bodies' outlines.
    pub dynamic: Color,
    /// Static bodies' outlines.
    pub fixed: Color,
    /// Kinematic bodies' outlines.
    pub kinematic: Color,
    /// Sensors' outlines.
    pub sensor: Color,
    /// Contact points and normals; `None` draws none.
    pub contacts: Option<Color>,
    /// Joints, anchor to anchor; `None` draws none.
    pub joints: Option<Color>,
}

impl Default for PassoDebugDraw {
    fn default() -> Self {
        Self {
            enabled: true,
            dynamic: Color::srgb(0.95, 0.75, 0.3),
            fixed: Color::srgb(0.55, 0.6, 0.7),
            kinematic: Color::srgb(0.4, 0.8, 1.0),
            sensor: Color::srgb(0.5, 1.0, 0.5),
            contacts: Some(Color::srgb(1.0, 0.3, 0.3)),
            joints: Some(Color::srgb(1.0, 1.0, 1.0)),
        }
    }
}

fn draw(world: Res<PassoWorld>, style: Res<PassoDebugDraw>, mut gizmos: Gizmos) {
    if !style.enabled {
        return;
    }
    for body in world.bodies() {
        let Some(shape) = body.shape else { continue };
        let colour = match (body.sensor, body.kind) {
            (true, _) => style.sensor,
            (_, passo::BodyKind::Dynamic) => style.dynamic,
            (_, passo::BodyKind::Static) => style.fixed,
            (_, passo::BodyKind::Kinematic) => style.kinematic,
        };
        outline(&mut gizmos, shape, to_bevy(body.position), colour);
    }
    if let Some(colour) = style.contacts {
        for contact in world.contacts() {
            let normal = to_bevy(contact.normal);
            for &point in &contact.points[..usize::from(contact.point_count)] {
                let point = to_bevy(point);
                gizmos.circle_2d(Isometry2d::from_translation(point), 0.04, colour);
                gizmos.line_2d(point, point + normal * 0.2, colour);
            }
        }
    }
    if let Some(colour) = style.joints {
        for (_, joint) in world.joints() {
            gizmos.line_2d(to_bevy(joint.anchors.0), to_bevy(joint.anchors.1), colour);
        }
    }
}

/// A shape's outline at `at`.
fn outline(gizmos: &mut Gizmos, shape: Shape, at: Vec2, colour: Color) {
    match shape {
        Shape::Circle { radius } => {
            gizmos.circle_2d(Isometry2d::from_translation(at), radius, colour);
        }
        Shape::Box { half_extents } => {
            gizmos.rect_2d(
                Isometry2d::from_translation(at),
                to_bevy(half_extents) * 2.0,
                colour,
            );
        }
        Shape::Capsule {
            half_segment,
            radius,
        } => {
            let half = to_bevy(half_segment);
            let side = half.perp().normalize_or_zero() * radius;
            gizmos.circle_2d(Isometry2d::from_translation(at + half), radius, colour);
            gizmos.circle_2d(Isometry2d::from_translation(at - half), radius, colour);
            gizmos.line_2d(at - half + side, at + half + side, colour);
            gizmos.line_2d(at - half - side, at + half - side, colour);
        }
        Shape::Segment { half } | Shape::ChainSegment { half, .. } => {
            let half = to_bevy(half);
            gizmos.line_2d(at - half, at + half, colour);
        }
        Shape::Polygon(polygon) => {
            let points = polygon.vertices().iter().map(|&p| at + to_bevy(p));
            let first = polygon.vertices().first().map(|&p| at + to_bevy(p));
            gizmos.linestrip_2d(points.chain(first), colour);
        }
    }
}
