//! The per-term breakdown of one pixel's radiance (the viewer's pixel probe).

use glam::DVec3;

/// One light's share at the probed hit, with every factor of the model kept apart.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LightTerm {
    pub light: u32,
    pub f_att: f64,
    pub spot: f64,
    /// V_j per channel (filtered shadows).
    pub visibility: DVec3,
    /// I_a,j·k_a.
    pub ambient: DVec3,
    /// I_d,j·k_d·max(N·L, 0).
    pub diffuse: DVec3,
    /// I_s,j·k_s·spec_j.
    pub specular: DVec3,
    /// f_att·S·[ambient + V·(diffuse + specular)], what the light adds.
    pub contribution: DVec3,
}

/// The radiance of a camera ray split into the terms of the model at its first hit.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Breakdown {
    /// Object id of the first hit, `NO_HIT` for background.
    pub object_id: u32,
    pub material: u32,
    pub t: f64,
    pub point: DVec3,
    /// Shading normal turned towards the viewer.
    pub normal: DVec3,
    /// E_m.
    pub emission: DVec3,
    /// I_a·k_a.
    pub ambient: DVec3,
    pub lights: Vec<LightTerm>,
    /// k_r·I_r (including the k_t share under total internal reflection).
    pub reflected: DVec3,
    /// k_t·I_t.
    pub transmitted: DVec3,
    /// The pixel radiance: the sum of all the above (or the background).
    pub total: DVec3,
}

impl Breakdown {
    /// Sum of the listed terms, to check against `total`.
    pub fn sum_of_terms(&self) -> DVec3 {
        self.emission
            + self.ambient
            + self.lights.iter().map(|l| l.contribution).sum::<DVec3>()
            + self.reflected
            + self.transmitted
    }
}
