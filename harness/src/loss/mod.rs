//! Joint power loss against the amplitude of an output at resonance (thesis §5.4–5.5).

use serde::{Deserialize, Serialize};

/// The `[loss_study]` table of a scene.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LossStudySpec {
    /// Named output whose amplitude is set (e.g. the sonotrode's blade-side end face).
    pub output: String,
}
