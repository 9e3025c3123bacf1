//! The UEXTERNALDB configuration file of the exported job (`jointlin.cfg`, keys of
//! fortran-shim/README.md): the scene's `[iteration]` (the start amplitude, the
//! tolerance as `rtol`, the scheme, the passes), the steady-state step's number, and the
//! files of the pass-by-pass scheme (each pass its own job). `jointlin run DECK.inp`
//! reads the same file (`input::deck::config`), so the harness iterates as the job does.

use super::num;
use crate::input::scene::Scene;
use crate::names::SchemeName;

/// The configuration text of `scene`'s job (deck file `deck_name`).
pub fn text(scene: &Scene, deck_name: &str) -> String {
    let it = &scene.spec.iteration;
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
         rtol = {tol}   # [iteration] tolerance: |a - a*| <= rtol max(a, a*)\n\
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
        passes = it.max_passes,
    )
}
