//! Validation of a parsed scene: every value against its allowed range,
//! with errors that name the field.

use crate::error::SceneError;
use crate::format::{BodySpec, ChainSpec, Generator, MAX_BODIES, SceneFile};
use passo_physics::glam::Vec2;
use passo_physics::{BodyKind, Shape};

struct Check<'a> {
    source: &'a str,
}

impl Check<'_> {
    fn fail(&self, field: &str, message: String) -> SceneError {
        SceneError::Invalid {
            source_name: self.source.to_owned(),
            field: field.to_owned(),
            message,
        }
    }

    fn range(&self, field: &str, v: f32, ok: bool, allowed: &str) -> Result<(), SceneError> {
        if !(v.is_finite() || v == f32::INFINITY && allowed.contains("inf")) {
            return Err(self.fail(field, format!("must be finite ({allowed}), got {v}")));
        }
        if ok {
            Ok(())
        } else {
            Err(self.fail(field, format!("must be {allowed}, got {v}")))
        }
    }

    fn positive(&self, field: &str, v: f32, unit: &str) -> Result<(), SceneError> {
        self.range(field, v, v > 0.0, &format!("> 0 {unit}"))
    }

    fn non_negative(&self, field: &str, v: f32, unit: &str) -> Result<(), SceneError> {
        self.range(field, v, v >= 0.0, &format!(">= 0 {unit}"))
    }

    fn finite_vec(&self, field: &str, v: Vec2) -> Result<(), SceneError> {
        if v.is_finite() {
            Ok(())
        } else {
            Err(self.fail(field, format!("must be finite, got ({}, {})", v.x, v.y)))
        }
    }
}

impl SceneFile {
    /// The bodies the file lists and its generators make (not its level's).
    pub(crate) fn listed_bodies(&self) -> u64 {
        let made = self.generators.iter().map(Generator::count);
        let segments = self.chains.iter().map(ChainSpec::segments);
        made.chain(segments)
            .fold(self.bodies.len() as u64, u64::saturating_add)
    }

    /// Checks every value; the error names the field and the allowed range.
    pub fn validate(&self, source: &str) -> Result<(), SceneError> {
        let c = Check { source };
        if !(self.rate_hz.is_finite() && (1.0..=10_000.0).contains(&self.rate_hz)) {
            return Err(c.fail(
                "rate_hz",
                format!("must be in [1, 10000] Hz, got {:?}", self.rate_hz),
            ));
        }
        c.non_negative("min_speed", self.min_speed, "m/s")?;
        c.range(
            "max_speed",
            self.max_speed,
            self.max_speed > 0.0,
            "> 0 m/s or inf",
        )?;
        self.validate_forces(&c)?;
        if let Some(t) = &self.tilemap {
            if t.file.is_some() == t.ascii.is_some() {
                return Err(c.fail(
                    "tilemap",
                    "needs exactly one of `file` and `ascii`".to_owned(),
                ));
            }
            c.positive("tilemap.cell", t.cell, "m")?;
            c.finite_vec("tilemap.origin", t.origin)?;
            if t.kind == BodyKind::Dynamic {
                return Err(c.fail("tilemap.kind", "must be Static or Kinematic".to_owned()));
            }
            if let Some(path) = &t.path {
                c.finite_vec("tilemap.path.by", path.by)?;
                c.positive("tilemap.path.period", path.period, "s")?;
                if t.kind != BodyKind::Kinematic {
                    return Err(c.fail("tilemap.path", "is for `kind: Kinematic` maps".to_owned()));
                }
            }
        }
        if let Some(contacts) = &self.collisions {
            // A scene's own range first, so `substeps: 0` is told the
            // range a scene allows, not the wider one the physics does.
            if !(1..=64).contains(&contacts.substeps) {
                return Err(c.fail(
                    "collisions.substeps",
                    format!("must be in [1, 64], got {}", contacts.substeps),
                ));
            }
            contacts
                .validate()
                .map_err(|e| c.fail("collisions", physics_message(&e)))?;
        }
        if let Some(camera) = &self.camera {
            c.finite_vec("camera.min", camera.min)?;
            c.finite_vec("camera.max", camera.max)?;
            if !(camera.min.x < camera.max.x && camera.min.y < camera.max.y) {
                return Err(c.fail("camera", "must have min < max on both axes".to_owned()));
            }
        }
        for (i, body) in self.bodies.iter().enumerate() {
            body.validate(&c, &format!("bodies[{i}]"))?;
        }
        for (i, g) in self.generators.iter().enumerate() {
            g.validate(&c, &format!("generators[{i}]"))?;
        }
        for (i, chain) in self.chains.iter().enumerate() {
            chain.validate(&c, &format!("chains[{i}]"))?;
        }
        let total = self.listed_bodies();
        if total > MAX_BODIES as u64 {
            // (A file's `bodies` list alone is held to the limit while read.)
            let field = if self.generators.is_empty() {
                "bodies"
            } else {
                "generators"
            };
            return Err(c.fail(
                field,
                format!("make {total} bodies; at most {} are allowed", MAX_BODIES),
            ));
        }
        self.validate_in_world(&c)
    }

    /// Checks each body the file lists and its generators make as the
    /// world it builds will (its place within the world's coordinates, its
    /// speeds against the world's limits, a platform's path against the
    /// world's `max_speed`): a file that validates builds.
    fn validate_in_world(&self, c: &Check<'_>) -> Result<(), SceneError> {
        let settings = crate::build::settings(self);
        // What `World::new` checks of them together (a minimum speed above
        // the maximum).
        settings
            .validate()
            .map_err(|e| c.fail("min_speed", physics_message(&e)))?;
        let check = |spec: &BodySpec, position: Vec2, path: &dyn Fn() -> String| {
            let def = crate::build::body_def(spec, position);
            settings
                .check_body(&def)
                .map_err(|e| c.fail(&path(), physics_message(&e)))?;
            if let Some(p) = &spec.path {
                p.check_speed(self.max_speed)
                    .map_err(|m| c.fail(&format!("{}.path", path()), m))?;
            }
            Ok(())
        };
        for (i, body) in self.bodies.iter().enumerate() {
            check(body, body.position, &|| format!("bodies[{i}]"))?;
        }
        for (i, g) in self.generators.iter().enumerate() {
            let mut first = Ok(());
            crate::generate::generate(g, |spec, position| {
                if first.is_ok() {
                    first = check(spec, position, &|| format!("generators[{i}]"));
                }
            });
            first?;
        }
        if let Some(path) = self.tilemap.as_ref().and_then(|t| t.path) {
            path.check_speed(self.max_speed)
                .map_err(|m| c.fail("tilemap.path", m))?;
        }
        self.validate_joints(c, settings)
    }

    /// The joints: each names bodies the scene makes and is one the
    /// physics takes, checked in a world of the bodies they name. (A map
    /// file's objects may be named too: with one, the names are checked
    /// when the scene is built.)
    fn validate_joints(
        &self,
        c: &Check<'_>,
        settings: passo_physics::WorldSettings,
    ) -> Result<(), SceneError> {
        if self.joints.is_empty() {
            return Ok(());
        }
        if self.collisions.is_none() {
            return Err(c.fail(
                "joints",
                "need `collisions`: joints are solved with the contacts".to_owned(),
            ));
        }
        if self.tilemap.as_ref().is_some_and(|t| t.file.is_some()) {
            return Ok(());
        }
        let mut world = passo_physics::World::new(settings)
            .map_err(|e| c.fail("joints", physics_message(&e)))?;
        let mut placed: Vec<(String, passo_physics::BodyId, Vec2)> = Vec::new();
        for (i, joint) in self.joints.iter().enumerate() {
            let field = format!("joints[{i}]");
            let mut find = |name: &str| -> Result<(passo_physics::BodyId, Vec2), String> {
                if let Some((_, id, at)) = placed.iter().find(|(n, _, _)| n == name) {
                    return Ok((*id, *at));
                }
                let (spec, at) = self
                    .first_named(name)
                    .ok_or_else(|| format!("no body is named {name:?}"))?;
                let def = crate::build::body_def(&spec, at);
                let id = world.add_body(def).map_err(|e| physics_message(&e))?;
                placed.push((name.to_owned(), id, at));
                Ok((id, at))
            };
            let def = crate::build::joint_def(joint, &mut find).map_err(|m| c.fail(&field, m))?;
            world
                .add_joint(def)
                .map_err(|e| c.fail(&field, physics_message(&e)))?;
        }
        Ok(())
    }

    /// The first body the scene makes with this name (listed bodies come
    /// before generated ones), and where.
    fn first_named(&self, name: &str) -> Option<(BodySpec, Vec2)> {
        if let Some(b) = self.bodies.iter().find(|b| b.name.as_deref() == Some(name)) {
            return Some((b.clone(), b.position));
        }
        for g in &self.generators {
            let mut first = None;
            crate::generate::generate(g, |spec, position| {
                if first.is_none() && spec.name.as_deref() == Some(name) {
                    first = Some((spec.clone(), position));
                }
            });
            if first.is_some() {
                return first;
            }
        }
        None
    }

    fn validate_forces(&self, c: &Check<'_>) -> Result<(), SceneError> {
        let f = &self.forces;
        if let Some(g) = f.gravity {
            c.finite_vec("forces.gravity", g)?;
        }
        if let Some(d) = &f.quadratic_drag {
            c.non_negative("forces.quadratic_drag.density", d.density, "kg/m³")?;
        }
        if let Some(d) = &f.linear_drag {
            c.non_negative("forces.linear_drag.coefficient", d.coefficient, "kg/s")?;
        }
        c.finite_vec("forces.wind", f.wind)?;
        if let Some(s) = &f.surface_friction {
            c.non_negative("forces.surface_friction.gravity", s.gravity, "m/s²")?;
        }
        if let Some(v) = f.force_field {
            c.finite_vec("forces.force_field", v)?;
        }
        if let Some(s) = &f.spring {
            c.finite_vec("forces.spring.anchor", s.anchor)?;
            c.non_negative("forces.spring.stiffness", s.stiffness, "N/m")?;
        }
        if let Some(g) = &f.central_gravity {
            c.finite_vec("forces.central_gravity.centre", g.centre)?;
            c.range("forces.central_gravity.gm", g.gm, true, "finite m³/s²")?;
        }
        Ok(())
    }
}

/// A physics error's message without the Rust type prefix.
fn physics_message(e: &passo_physics::PhysicsError) -> String {
    let text = e.to_string();
    match text.split_once("::") {
        Some((_, rest)) => format!("field {rest}"),
        None => text,
    }
}

/// Checks a body made elsewhere (a Tiled object) as a scene body is
/// checked; errors name `source` and `path`.
pub(crate) fn check_body(spec: &BodySpec, source: &str, path: &str) -> Result<(), SceneError> {
    spec.validate(&Check { source }, path)
}

impl BodySpec {
    fn validate(&self, c: &Check<'_>, path: &str) -> Result<(), SceneError> {
        let at = |field: &str| format!("{path}.{field}");
        if let Some(zone) = &self.zone {
            if !self.sensor || !matches!(self.shape, Some(Shape::Box { .. })) {
                return Err(c.fail(
                    &at("zone"),
                    "needs a sensor body with a Box shape".to_owned(),
                ));
            }
            zone.validate()
                .map_err(|e| c.fail(&at("zone"), physics_message(&e)))?;
        }
        if let Some(shape) = &self.shape {
            match *shape {
                Shape::Circle { radius } => c.positive(&at("shape.radius"), radius, "m")?,
                Shape::Box { half_extents } => {
                    c.positive(&at("shape.half_extents.x"), half_extents.x, "m")?;
                    c.positive(&at("shape.half_extents.y"), half_extents.y, "m")?;
                }
                Shape::Capsule {
                    half_segment,
                    radius,
                } => {
                    c.positive(&at("shape.radius"), radius, "m")?;
                    c.non_negative(&at("shape.half_segment.x"), half_segment.x, "m")?;
                    c.non_negative(&at("shape.half_segment.y"), half_segment.y, "m")?;
                    if half_segment.x > 0.0 && half_segment.y > 0.0 {
                        return Err(c.fail(
                            &at("shape.half_segment"),
                            "must have one component 0: (0, h) for an upright capsule, (h, 0) for a lying one"
                                .to_owned(),
                        ));
                    }
                }
                Shape::Segment { half } | Shape::ChainSegment { half, .. } => {
                    c.positive(&at("shape.half (its length)"), half.length(), "m")?;
                    if self.kind == passo_physics::BodyKind::Dynamic {
                        return Err(c.fail(
                            &at("shape"),
                            "a segment has no area: only a Static or Kinematic body may have one"
                                .to_owned(),
                        ));
                    }
                }
                // Checked as it was read.
                Shape::Polygon(_) => {
                    if self.kind == passo_physics::BodyKind::Dynamic {
                        return Err(c.fail(
                            &at("shape"),
                            "a polygon is level geometry: only a Static or Kinematic body may have one"
                                .to_owned(),
                        ));
                    }
                }
            }
        }
        if self.mass.is_some() && self.density.is_some() {
            return Err(c.fail(path, "gives both `mass` and `density`; give one".to_owned()));
        }
        if let Some(mass) = self.mass {
            c.positive(&at("mass"), mass, "kg")?;
        }
        if let Some(density) = self.density {
            c.positive(&at("density"), density, "kg/m²")?;
            match &self.shape {
                None => {
                    return Err(c.fail(
                        &at("density"),
                        "needs a `shape` to give the area".to_owned(),
                    ));
                }
                Some(shape) => {
                    let mass = density * shape.area();
                    if !(mass.is_finite() && mass > 0.0) {
                        return Err(c.fail(
                            &at("density"),
                            format!("gives a mass of {mass} kg; it must be finite and > 0"),
                        ));
                    }
                }
            }
        }
        c.finite_vec(&at("position"), self.position)?;
        c.finite_vec(&at("velocity"), self.velocity)?;
        let m = &self.material;
        check_surface(c, &at, m)?;
        c.non_negative(&at("material.drag_area"), m.drag_area, "m²")?;
        if let Some(v) = self.min_speed {
            c.non_negative(&at("min_speed"), v, "m/s")?;
        }
        if let Some(v) = self.max_speed {
            c.range(&at("max_speed"), v, v > 0.0, "> 0 m/s or inf")?;
        }
        if self.sensor && self.shape.is_none() {
            return Err(c.fail(&at("sensor"), "needs a `shape`".to_owned()));
        }
        if let Some(n) = self.one_way {
            c.finite_vec(&at("one_way"), n)?;
            if n == Vec2::ZERO || self.kind == BodyKind::Dynamic {
                return Err(c.fail(
                    &at("one_way"),
                    "must be a non-zero direction on a Static or Kinematic body".to_owned(),
                ));
            }
        }
        if self.bullet && self.kind != BodyKind::Dynamic {
            return Err(c.fail(&at("bullet"), "is for `kind: Dynamic` bodies".to_owned()));
        }
        if let Some(path) = &self.path {
            c.finite_vec(&at("path.by"), path.by)?;
            c.positive(&at("path.period"), path.period, "s")?;
            if self.kind != BodyKind::Kinematic {
                return Err(c.fail(&at("path"), "is for `kind: Kinematic` bodies".to_owned()));
            }
        }
        Ok(())
    }
}

impl ChainSpec {
    /// The segments (bodies) it makes.
    pub(crate) fn segments(&self) -> u64 {
        let n = self.points.len() as u64;
        if self.closed { n } else { n.saturating_sub(1) }
    }

    fn validate(&self, c: &Check<'_>, path: &str) -> Result<(), SceneError> {
        let at = |field: &str| format!("{path}.{field}");
        let least = if self.closed { 3 } else { 2 };
        if self.points.len() < least {
            return Err(c.fail(
                &at("points"),
                format!(
                    "has {} points; a chain needs at least {least}",
                    self.points.len()
                ),
            ));
        }
        for (i, p) in self.points.iter().enumerate() {
            c.finite_vec(&at(&format!("points[{i}]")), *p)?;
            if i > 0 && *p == self.points[i - 1] {
                return Err(c.fail(
                    &at(&format!("points[{i}]")),
                    "is the point before it again: a segment needs two ends apart".to_owned(),
                ));
            }
        }
        if self.kind == BodyKind::Dynamic {
            return Err(c.fail(
                &at("kind"),
                "must be Static or Kinematic: a chain has no area, so no mass".to_owned(),
            ));
        }
        check_surface(c, &at, &self.material)
    }
}

/// A material's restitution, in [0, 1], and friction, >= 0; `at` names
/// a field of the body or chain.
fn check_surface(
    c: &Check<'_>,
    at: &dyn Fn(&str) -> String,
    m: &crate::format::Material,
) -> Result<(), SceneError> {
    c.range(
        &at("material.restitution"),
        m.restitution,
        (0.0..=1.0).contains(&m.restitution),
        "in [0, 1]",
    )?;
    c.non_negative(&at("material.friction"), m.friction, "")
}

impl Generator {
    fn validate(&self, c: &Check<'_>, path: &str) -> Result<(), SceneError> {
        let at = |field: &str| format!("{path}.{field}");
        let count = |field: &str, n: u32| {
            if n >= 1 {
                Ok(())
            } else {
                Err(c.fail(&at(field), "must be >= 1, got 0".to_owned()))
            }
        };
        match self {
            Self::Grid {
                origin,
                columns,
                rows,
                spacing,
                body,
            } => {
                count("columns", *columns)?;
                count("rows", *rows)?;
                c.finite_vec(&at("origin"), *origin)?;
                c.finite_vec(&at("spacing"), *spacing)?;
                body.validate(c, &at("body"))
            }
            Self::Pyramid {
                base,
                origin,
                gap,
                body,
            } => {
                count("base", *base)?;
                c.finite_vec(&at("origin"), *origin)?;
                c.non_negative(&at("gap"), *gap, "m")?;
                if body.shape.is_none() {
                    return Err(c.fail(&at("body.shape"), "is needed to stack bodies".to_owned()));
                }
                body.validate(c, &at("body"))
            }
            Self::Rain {
                count: n,
                origin,
                columns,
                spacing,
                jitter,
                body,
                ..
            } => {
                count("count", *n)?;
                count("columns", *columns)?;
                c.finite_vec(&at("origin"), *origin)?;
                c.finite_vec(&at("spacing"), *spacing)?;
                c.non_negative(&at("jitter"), *jitter, "m")?;
                body.validate(c, &at("body"))
            }
        }
    }
}
