//! The model variations the studies make, each a new [`Job`] on the changed input with
//! the same settings: a screw's tightening torque (the loss study's torques), the mesh
//! refined and the contact law sampled over the areas or not (its mesh study), the
//! interfaces' tangential parameters scaled (its calibration), an excitation's amplitude
//! and every box's mesh (the validation's cases).

use std::sync::Arc;

use super::Job;
use crate::input::scene::SceneFile;

impl Job {
    /// This job on its input changed by `edit`.
    fn changed(&self, edit: impl FnOnce(&mut SceneFile)) -> Job {
        let mut scene = self.source.as_ref().clone();
        edit(&mut scene.spec);
        Job {
            settings: self.settings.clone(),
            source: Arc::new(scene),
        }
    }

    /// Each body's mesh divisions (x, y, z) in the input's order (`None`: not a box).
    pub fn divisions(&self) -> Vec<Option<[usize; 3]>> {
        self.source
            .spec
            .bodies
            .iter()
            .map(|b| b.divisions)
            .collect()
    }

    /// The tightening torque (force·length) of screw `name`, if the input has it.
    pub fn screw_torque(&self, name: &str) -> Option<f64> {
        (self.source.spec.screws.iter())
            .find(|s| s.name == name)
            .map(|s| s.torque)
    }

    /// This job with screw `name` tightened to `torque` (force·length); `None` if the
    /// input has no such screw.
    pub fn with_screw_torque(&self, name: &str, torque: f64) -> Option<Job> {
        self.screw_torque(name)?;
        Some(self.changed(|s| {
            for screw in s.screws.iter_mut().filter(|s| s.name == name) {
                screw.torque = torque;
            }
        }))
    }

    /// This job with the divisions of the boxes `select` accepts (by body name)
    /// multiplied by `factor` along the `axes` (x, y, z) that are true.
    pub fn refined(&self, factor: usize, select: impl Fn(&str) -> bool, axes: [bool; 3]) -> Job {
        self.changed(|s| {
            for b in s.bodies.iter_mut().filter(|b| select(&b.name)) {
                if let Some(d) = &mut b.divisions {
                    for (n, on) in d.iter_mut().zip(axes) {
                        if on {
                            *n *= factor;
                        }
                    }
                }
            }
        })
    }

    /// This job with excitation `index` (input order) at `amplitude` (force); `None` if
    /// the input has no such excitation.
    pub fn with_excitation_amplitude(&self, index: usize, amplitude: f64) -> Option<Job> {
        self.source.spec.excitation.get(index)?;
        Some(self.changed(|s| s.excitation[index].amplitude = amplitude))
    }

    /// This job with every box meshed by `divisions` (x, y, z).
    pub fn with_box_divisions(&self, divisions: [usize; 3]) -> Job {
        self.changed(|s| {
            for b in s.bodies.iter_mut().filter(|b| b.divisions.is_some()) {
                b.divisions = Some(divisions);
            }
        })
    }

    /// This job with every interface's k_T0 per area and friction coefficient μ scaled
    /// by `k_t0` and `mu`.
    pub fn with_interfaces_scaled(&self, k_t0: f64, mu: f64) -> Job {
        self.changed(|s| {
            for i in &mut s.interfaces {
                i.k_t0_per_area *= k_t0;
                i.mu *= mu;
            }
        })
    }

    /// This job with every interface's contact law sampled over `area_samples` ×
    /// `area_samples` points of each contact area (`None`: node-based).
    pub fn with_area_samples(&self, area_samples: Option<usize>) -> Job {
        self.changed(|s| {
            for i in &mut s.interfaces {
                i.area_samples = area_samples;
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::scene::Scene;

    /// Only the selected axes of the selected boxes change.
    #[test]
    fn refined_multiplies_only_the_selected_divisions() {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife-coarse.toml");
        let job = Job::from(&Scene::load(&path).unwrap());
        let r = job.refined(3, |name| name.starts_with("jaw_"), [true, false, true]);
        let bodies = |j: &Job| j.source.spec.bodies.clone();
        assert!(bodies(&job).iter().any(|b| b.name.starts_with("jaw_")));
        for (a, b) in bodies(&job).iter().zip(&bodies(&r)) {
            let (da, db) = (a.divisions.unwrap(), b.divisions.unwrap());
            let want = if a.name.starts_with("jaw_") {
                [3 * da[0], da[1], 3 * da[2]]
            } else {
                da
            };
            assert_eq!(db, want, "{}", a.name);
        }
        assert_eq!(r.settings, job.settings);
    }
}
