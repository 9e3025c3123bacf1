//! The UEXTERNALDB configuration file of the exported job (`jointlin.cfg`, keys of
//! fortran-shim/README.md): the scene's `[iteration]` (the start amplitude, the
//! tolerance as `rtol`, the scheme, the passes), the absolute tolerance `atol` the
//! harness's thesis mode uses (a direction that is never excited, a* = 0, converges only
//! with one), the steady-state step's number, and the files of the pass-by-pass scheme
//! (each pass its own job). `jointlin run DECK.inp` reads the same file
//! (`input::deck::config`), so the harness iterates as the job does.

use super::{num, ExportError};
use crate::input::scene::Scene;
use crate::model::Problem;
use crate::names::SchemeName;
use crate::solve::static_step;
use crate::solve::sweep::{scale::stuck_scale, Setup, ATOL_REL};

/// The absolute amplitude tolerance (length) of `scene`'s thesis-mode sweep: ATOL_REL
/// times the smallest over the sweep of the stuck response's largest contact amplitude
/// (`solve::sweep::scale`), after the static step.
pub fn atol(scene: &Scene, p: &Problem) -> Result<f64, ExportError> {
    let fail = |e: String| ExportError::Solve(format!("{}: the amplitude scale: {e}", scene.file));
    let stat = static_step::solve(p, scene.spec.effects.normal_contact_nonlinearity)
        .map_err(|e| fail(e.to_string()))?;
    let mut setup = Setup::new(p, &stat, &scene.spec.effects).map_err(|e| fail(e.to_string()))?;
    let scale = stuck_scale(&mut setup, &scene.frequencies()).map_err(|e| fail(e.to_string()))?;
    Ok(ATOL_REL * scale)
}

/// The configuration text of `scene`'s job (deck file `deck_name`, absolute tolerance
/// `atol`, length).
pub fn text(scene: &Scene, deck_name: &str, atol: f64) -> String {
    let it = &scene.spec.iteration;
    // atol to three digits: a tolerance, and the same text wherever the solver's last
    // digits differ (the committed examples are compared with fresh exports).
    let scheme = match it.scheme {
        SchemeName::Direct => "direct",
        SchemeName::Relaxation => "relaxation",
        SchemeName::Secant => "secant",
    };
    format!(
        "# UEXTERNALDB configuration of the Abaqus job {deck_name}, written by\n\
         # `jointlin export {file}` (keys: fortran-shim/README.md). The shim finds it as\n\
         # $JOINTLIN_CONFIG, else ./jointlin.cfg in the job directory; `jointlin run\n\
         # {deck_name}` reads the iteration settings from it too.\n\
         initial_amplitude = {a}   # [iteration] initial_amplitude ({len})\n\
         rtol = {tol}   # [iteration] tolerance: |a - a*| <= rtol max(a, a*) + atol\n\
         atol = {atol:.2e}   # ({len}) {rel} x the smallest stuck contact amplitude, as `jointlin run --mode thesis`\n\
         scheme = {scheme}\n\
         max_passes = {passes}\n\
         sweep_step = 2   # the *STEADY STATE DYNAMICS step\n\
         kinc_numbering = sequential   # a re-run pass is its own job, numbering its increments 1..m\n\
         restart_file = jointlin.restart\n\
         action_file = jointlin.next\n",
        file = scene.file,
        a = num(it.initial_amplitude),
        len = scene.spec.units.length,
        tol = num(it.tolerance),
        rel = num(ATOL_REL),
        passes = it.max_passes,
    )
}
