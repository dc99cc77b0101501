//! A rigid body that can rock: its mass, inertia and the geometry of its base, and the numbers
//! Housner's analysis derives from them. A free-standing block in the wall's plane is one; so is
//! the part of a wall above a bed joint, rocking across the wall's plane
//! ([`crate::topology::sections`]).

use crate::error::SimulationError;

/// A rigid body standing on a flat base with two edges (corners in the plane of motion), its
/// centroid above the middle of the base. Symbols of Housner (1963): b, h_c, R, alpha, p.
#[derive(Debug, Clone, PartialEq)]
pub struct RockingBody {
    /// Name in outputs.
    pub name: String,
    /// Mass (kg).
    pub mass_kg: f64,
    /// Moment of inertia about the centroid, for rotation in the plane of motion (kg m2).
    pub inertia_kg_m2: f64,
    /// Half the width of the base, b (m).
    pub half_base_m: f64,
    /// Height of the centroid above the base, h_c (m).
    pub centroid_height_m: f64,
    /// Friction coefficient of the base (static = kinetic).
    pub friction: f64,
    /// Factor on Housner's coefficient of restitution (1: Housner's law as it is; measured
    /// values are often lower).
    pub restitution_factor: f64,
    /// Gravity (m/s2).
    pub g_m_s2: f64,
}

impl RockingBody {
    /// A rectangular block of width `width_m`, height `height_m` and mass `mass_kg`.
    pub fn rectangle(
        name: &str,
        width_m: f64,
        height_m: f64,
        mass_kg: f64,
        friction: f64,
        g_m_s2: f64,
    ) -> RockingBody {
        RockingBody {
            name: name.to_string(),
            mass_kg,
            inertia_kg_m2: mass_kg * (width_m * width_m + height_m * height_m) / 12.0,
            half_base_m: 0.5 * width_m,
            centroid_height_m: 0.5 * height_m,
            friction,
            restitution_factor: 1.0,
            g_m_s2,
        }
    }

    /// The part of a wall above a bed joint, rocking across the wall's plane on the joint's
    /// edges (its base is the wall's thickness).
    pub fn section(
        section: &crate::topology::sections::Section,
        restitution_factor: f64,
    ) -> RockingBody {
        RockingBody {
            name: section.name.clone(),
            mass_kg: section.mass_kg,
            inertia_kg_m2: section.inertia_kg_m2,
            half_base_m: 0.5 * section.thickness_m,
            centroid_height_m: section.centroid_height_m,
            friction: section.friction,
            restitution_factor,
            g_m_s2: section.g_m_s2,
        }
    }

    /// Checks that the numbers describe a body (positive and finite; a factor in [0, 1]).
    pub fn validate(&self) -> Result<(), SimulationError> {
        let positive = [
            ("mass_kg", self.mass_kg),
            ("inertia_kg_m2", self.inertia_kg_m2),
            ("half_base_m", self.half_base_m),
            ("centroid_height_m", self.centroid_height_m),
            ("friction", self.friction),
            ("g_m_s2", self.g_m_s2),
        ];
        for (what, x) in positive {
            if !(x.is_finite() && x > 0.0) {
                return Err(SimulationError::Body {
                    body: self.name.clone(),
                    what,
                    value: x,
                    rule: "it must be a positive number",
                });
            }
        }
        if !(0.0..=1.0).contains(&self.restitution_factor) {
            return Err(SimulationError::Body {
                body: self.name.clone(),
                what: "rocking restitution factor",
                value: self.restitution_factor,
                rule: "it must lie in [0, 1]",
            });
        }
        Ok(())
    }

    /// R: distance from a base corner to the centroid (m).
    pub fn size_m(&self) -> f64 {
        self.half_base_m.hypot(self.centroid_height_m)
    }

    /// alpha = atan(b / h_c): the angle at which the centroid stands over a corner (rad).
    pub fn slenderness_rad(&self) -> f64 {
        self.half_base_m.atan2(self.centroid_height_m)
    }

    /// b / h_c: the ground acceleration, in g, that lifts the body off a base that holds it
    /// (Housner's g tan alpha).
    pub fn uplift_ratio(&self) -> f64 {
        self.half_base_m / self.centroid_height_m
    }

    /// I_O = I_G + m R^2: moment of inertia about a base corner (kg m2).
    pub fn corner_inertia_kg_m2(&self) -> f64 {
        let r = self.size_m();
        self.inertia_kg_m2 + self.mass_kg * r * r
    }

    /// p = sqrt(m g R / I_O): the frequency parameter (rad/s); 3 g / (4 R) under the root for a
    /// rectangle.
    pub fn frequency_parameter_rad_s(&self) -> f64 {
        (self.mass_kg * self.g_m_s2 * self.size_m() / self.corner_inertia_kg_m2()).sqrt()
    }

    /// Housner's coefficient of restitution: the ratio of angular velocities across an impact
    /// that keeps the angular momentum about the new pivot, r = 1 - 2 m b^2 / I_O (1 - 1.5
    /// sin^2 alpha for a rectangle), before the factor.
    pub fn housner_restitution(&self) -> f64 {
        1.0 - 2.0 * self.mass_kg * self.half_base_m * self.half_base_m / self.corner_inertia_kg_m2()
    }

    /// The time scale 1/p (s): ties and tolerances are measured against it.
    pub fn time_scale_s(&self) -> f64 {
        1.0 / self.frequency_parameter_rad_s()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rectangle_has_housners_numbers() {
        let b = RockingBody::rectangle("B", 0.5, 2.0, 100.0, 0.7, 9.81);
        let r = (0.25f64 * 0.25 + 1.0).sqrt();
        let alpha = 0.25f64.atan();
        assert!((b.size_m() - r).abs() < 1e-15);
        assert!((b.slenderness_rad() - alpha).abs() < 1e-15);
        let p2 = 3.0 * 9.81 / (4.0 * r);
        assert!((b.frequency_parameter_rad_s().powi(2) - p2).abs() < 1e-13 * p2);
        let housner = 1.0 - 1.5 * alpha.sin().powi(2);
        assert!((b.housner_restitution() - housner).abs() < 1e-15);
    }
}
