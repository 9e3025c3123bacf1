//! `make install` into a temporary prefix, then what a user of the install tree does:
//!
//! * the tree: `bin/jointlin` runs; `libjointlin.so` → `libjointlin.so.MAJOR` →
//!   `libjointlin.so.VERSION` with the SONAME `libjointlin.so.MAJOR`; the installed
//!   library is stripped (no debug sections, no symbol table; a fraction of cargo's
//!   build, sizes printed) and its debug info sits in `lib/.debug`, linked by
//!   `.gnu_debuglink`;
//! * the README's C and Fortran examples built with `pkg-config --cflags --libs jointlin`
//!   and run (they load the library by its SONAME through the rpath);
//! * the installed shim rebuilt from `share/jointlin/fortran-shim` with other flags, its
//!   `shim_check` run against the installed library;
//! * an Abaqus user library linked with the `link_sl` addition of
//!   examples/abaqus/abaqus_v6.env by gcc alone (no Fortran driver adding its runtime),
//!   then loaded with dlopen(RTLD_NOW) by a stand-in of the Abaqus executable
//!   (harness/c/abaqus_loader.c): every symbol resolves and UEXTERNALDB and UINTER run.
//!
//! The guides (docs/c-fortran.md, docs/abaqus.md) must carry each example file verbatim.

mod hosts_common;
#[path = "tools/mod.rs"]
mod tools;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use hosts_common::*;
use jointlin::hysteresis::Rule;
use jointlin::law::TangentialLaw;
use jointlin::linearize::{linearize, Contact, Method};

/// The `jointlin` program cargo built in this target directory and profile (building it
/// when missing: `cargo test -p jointlin` alone does not).
fn harness_bin() -> PathBuf {
    let deps = std::env::current_exe()
        .unwrap()
        .parent()
        .unwrap()
        .to_path_buf();
    let profile_dir = deps.parent().unwrap().to_path_buf();
    let bin = profile_dir.join("jointlin");
    if !bin.is_file() {
        let profile = profile_dir
            .file_name()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        run_ok(
            Command::new(cargo)
                .args([
                    "build",
                    "-p",
                    "jointlin-harness",
                    "--bin",
                    "jointlin",
                    "--profile",
                ])
                .arg(if profile == "debug" { "dev" } else { &profile })
                .env("CARGO_TARGET_DIR", profile_dir.parent().unwrap())
                .current_dir(root()),
        );
    }
    bin
}

/// Installs once per test binary; returns the prefix.
fn prefix() -> &'static PathBuf {
    static P: OnceLock<PathBuf> = OnceLock::new();
    P.get_or_init(|| {
        let dir = build_dir("install");
        let prefix = dir.join("prefix");
        let _ = std::fs::remove_dir_all(&prefix);
        run_ok(
            Command::new("make")
                .arg("-s")
                .arg("-C")
                .arg(root())
                .arg("install")
                .arg(format!("PREFIX={}", prefix.display()))
                .arg(format!("JOINTLIN_LIBDIR={}", lib_dir().display()))
                .arg(format!("JOINTLIN_BIN={}", harness_bin().display()))
                .arg(format!("BUILD={}", dir.join("build").display())),
        );
        prefix
    })
}

fn text(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// `readelf -d` of a file (its dynamic section: SONAME, NEEDED, RUNPATH).
fn dynamic(file: &Path) -> String {
    text(&run_ok(Command::new("readelf").arg("-d").arg(file)))
}

fn library_version() -> String {
    format!("libjointlin.so.{}", env!("CARGO_PKG_VERSION"))
}

#[test]
fn install_places_program_library_header_modules_and_pkg_config_file() {
    let p = prefix();
    for f in [
        "bin/jointlin",
        "lib/libjointlin.so",
        "lib/libjointlin_abaqus.a",
        "lib/pkgconfig/jointlin.pc",
        "include/jointlin.h",
        "include/jointlin.mod",
        "include/jointlin_abaqus.mod",
        "share/jointlin/fortran-shim/Makefile",
        "share/jointlin/fortran-shim/shim_check.f90",
        "share/jointlin/fortran-shim/uinter.f",
        "share/jointlin/fortran-shim/uexternaldb.f",
        "share/jointlin/fortran-shim/abaqus_standin.f",
        "share/jointlin/fortran-shim/abaqus_standin_mpi.f90",
        "share/jointlin/fortran-shim/agree_mpi.f90",
        "share/jointlin/fortran-shim/agree_nompi.f90",
        "share/jointlin/examples/abaqus/abaqus_v6.env",
        "share/jointlin/examples/abaqus/block-on-plane/block.inp",
        "share/jointlin/examples/abaqus/block-on-plane/sweep.frq",
        "share/jointlin/examples/abaqus/block-on-plane/jointlin.cfg",
        "share/jointlin/examples/abaqus/three-beams/three-beams.inp",
    ] {
        assert!(p.join(f).is_file(), "{f} not installed");
    }
    let pc = std::fs::read_to_string(p.join("lib/pkgconfig/jointlin.pc")).unwrap();
    assert!(pc.contains(&format!("prefix={}", p.display())), "{pc}");
    assert!(pc.contains(&format!("Version: {}", env!("CARGO_PKG_VERSION"))));
    // The installed shim Makefile finds the installed library by default.
    let mk = std::fs::read_to_string(p.join("share/jointlin/fortran-shim/Makefile")).unwrap();
    let libdir = format!("JOINTLIN_LIBDIR ?= {}", p.join("lib").display());
    assert!(
        mk.lines().any(|l| l == libdir),
        "{libdir} not in the installed Makefile"
    );
}

#[test]
fn installed_tree_validates_from_another_directory_with_its_man_pages() {
    // The installed scenes are found beside the program: `jointlin validate` from a
    // directory without scenes/ runs the block case of the thesis.
    let p = prefix();
    let elsewhere = scratch("validate-elsewhere");
    let out = run_ok(
        Command::new(p.join("bin/jointlin"))
            .args(["validate", "--cases", "block-stick", "--out", "v"])
            .current_dir(&elsewhere),
    );
    assert!(text(&out).contains("block"), "{}", text(&out));
    assert!(elsewhere.join("v/validation.csv").is_file());
    for scene in [
        "block-stick.toml",
        "three-beams.toml",
        "hard",
        "beam-cb.toml",
    ] {
        assert!(
            p.join("share/jointlin/scenes").join(scene).exists(),
            "{scene}"
        );
    }
    // A man page per command, rendered by man(1) where it is installed.
    let man1 = p.join("share/man/man1");
    for page in [
        "jointlin.1",
        "jointlin-run.1",
        "jointlin-validate.1",
        "jointlin-matrices-import-ccx.1",
    ] {
        let text = std::fs::read_to_string(man1.join(page)).unwrap();
        assert!(
            text.contains(".TH") && text.contains(".SH SYNOPSIS"),
            "{page}"
        );
    }
    assert!(!man1.join("jointlin-help.1").exists());
}

/// The README's first tutorial (an Abaqus user's, docs/abaqus.md) from the installed tree
/// alone, in a directory without a checkout: export the installed block scene as a job,
/// copy the installed env file, user file and pass drivers beside it, run the passes
/// (a stand-in for Abaqus), check and run the job in the harness. Every installed scene checks from there too (the bolted lap's
/// takes its model from the installed examples/deck).
#[test]
fn installed_tree_runs_the_abaqus_tutorial_from_another_directory() {
    let p = prefix();
    let share = p.join("share/jointlin");
    let bin = p.join("bin/jointlin");
    let elsewhere = scratch("tutorial-elsewhere");
    run_ok(
        Command::new(&bin)
            .arg("export")
            .arg(share.join("scenes/block-on-plane.toml"))
            .args(["--inp", "job/block.inp"])
            .current_dir(&elsewhere),
    );
    let job = elsewhere.join("job");
    for f in ["block.inp", "sweep.frq", "jointlin.cfg"] {
        assert!(job.join(f).is_file(), "export wrote no {f}");
    }
    for f in ["abaqus_v6.env", "user.f", "passes.sh", "passes.py"] {
        let installed = share.join("examples/abaqus").join(f);
        std::fs::copy(&installed, job.join(f)).unwrap();
        if f.starts_with("passes") {
            let repo = std::fs::read(root().join("examples/abaqus").join(f)).unwrap();
            assert_eq!(
                std::fs::read(&installed).unwrap(),
                repo,
                "{f} installed as is"
            );
        }
    }
    let env = std::fs::read_to_string(job.join("abaqus_v6.env")).unwrap();
    assert!(
        env.contains(&format!("jointlin = '{}'", p.display())),
        "{env}"
    );
    let check = run_ok(
        Command::new(&bin)
            .args(["check", "job/block.inp"])
            .current_dir(&elsewhere),
    );
    let summary = text(&check);
    assert!(
        summary.contains("9 contact points") && summary.contains("14 frequencies"),
        "{summary}"
    );
    run_ok(
        Command::new(&bin)
            .args(["run", "job/block.inp", "--out", "job/harness", "--quiet"])
            .current_dir(&elsewhere),
    );
    let results = std::fs::read_to_string(job.join("harness/results.csv")).unwrap();
    assert!(
        results.starts_with("frequency_Hz,BLOCK_X_24_u1_amp_mm"),
        "{results}"
    );
    assert_eq!(results.lines().count(), 15, "14 frequencies");
    // The passes, by the installed driver in the exported job directory, with a stand-in
    // for Abaqus (harness/fortran/abaqus_job: one job of a two-point sweep through the
    // shim per call, reading this job's sweep.frq and jointlin.cfg).
    let frq = std::fs::read_to_string(job.join("sweep.frq")).unwrap();
    let passes = run_ok(
        Command::new("bash")
            .args(["passes.sh", "block.inp"])
            .env("ABAQUS", stand_in_abaqus())
            .current_dir(&job),
    );
    let answer = text(&passes);
    let jobs: usize = answer.trim().trim_start_matches("pass").parse().unwrap();
    assert!(
        jobs >= 3 && job.join(format!("pass{jobs}.dat")).is_file(),
        "{answer}"
    );
    assert_eq!(std::fs::read_to_string(job.join("sweep.frq")).unwrap(), frq);

    let mut scenes: Vec<PathBuf> = std::fs::read_dir(share.join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|f| f.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenes.sort();
    assert!(scenes.iter().any(|f| f.ends_with("bolted-lap.toml")));
    for scene in scenes {
        run_ok(
            Command::new(&bin)
                .arg("check")
                .arg(&scene)
                .current_dir(&elsewhere),
        );
    }
}

/// harness/fortran/abaqus_job built against this build's library (tests/pass_drivers.rs).
fn stand_in_abaqus() -> PathBuf {
    build_fortran_hosts(&build_dir("install-stand-in")).join("abaqus_job")
}

#[test]
fn installed_program_runs() {
    let out = run_ok(Command::new(prefix().join("bin/jointlin")).arg("--version"));
    assert_eq!(
        text(&out).trim(),
        format!("jointlin {}", env!("CARGO_PKG_VERSION"))
    );
    // It checks a scene, so it is the whole program, not a stub.
    let out = run_ok(
        Command::new(prefix().join("bin/jointlin"))
            .arg("check")
            .arg(root().join("scenes/three-beams.toml")),
    );
    assert!(!text(&out).is_empty());
}

#[test]
fn installed_library_has_its_soname_and_the_usual_links() {
    let lib = prefix().join("lib");
    let real = library_version();
    let link = |name: &str| std::fs::read_link(lib.join(name)).map(|t| t.display().to_string());
    assert_eq!(link("libjointlin.so").unwrap(), soname());
    assert_eq!(link(&soname()).unwrap(), real);
    assert!(std::fs::symlink_metadata(lib.join(&real))
        .unwrap()
        .is_file());
    let d = dynamic(&lib.join(&real));
    assert!(
        d.contains(&format!("Library soname: [{}]", soname())),
        "{d}"
    );
    // The SONAME's number is the C ABI's major version.
    assert_eq!(
        soname(),
        format!(
            "libjointlin.so.{}",
            jointlin::ffi::JOINTLIN_ABI_VERSION_MAJOR
        )
    );
}

fn sections(file: &Path) -> Vec<String> {
    let out = run_ok(Command::new("readelf").args(["-S", "-W"]).arg(file));
    text(&out)
        .lines()
        .filter_map(|l| {
            let l = l.trim_start();
            let rest = l.strip_prefix('[')?.split_once(']')?.1;
            rest.split_whitespace().next().map(str::to_string)
        })
        .collect()
}

#[test]
fn installed_library_is_stripped_and_its_debug_info_is_beside_it() {
    let lib = prefix().join("lib");
    let installed = lib.join(library_version());
    let built = lib_dir().join("libjointlin.so");
    let (small, big) = (
        std::fs::metadata(&installed).unwrap().len(),
        std::fs::metadata(&built).unwrap().len(),
    );
    println!("libjointlin.so: cargo's build {big} bytes, installed {small} bytes");
    let s = sections(&installed);
    assert!(s.iter().any(|n| n == ".dynsym"), "{s:?}");
    for gone in [".debug_info", ".debug_line", ".symtab"] {
        assert!(
            !s.iter().any(|n| n == gone),
            "{gone} in the installed library"
        );
    }
    assert!(s.iter().any(|n| n == ".gnu_debuglink"), "{s:?}");
    // The release profile keeps line tables (debug = 1): the build carries debug sections
    // and the installed copy is a fraction of it.
    assert!(sections(&built).iter().any(|n| n == ".debug_line"));
    assert!(
        small * 4 < big,
        "installed {small} bytes, built {big} bytes"
    );
    // The debug info gdb finds through .gnu_debuglink: lib/.debug/<name>.debug.
    let debug = lib
        .join(".debug")
        .join(format!("{}.debug", library_version()));
    let d = sections(&debug);
    assert!(d.iter().any(|n| n == ".debug_info"), "{d:?}");
    let link = run_ok(
        Command::new("readelf")
            .args(["-p", ".gnu_debuglink"])
            .arg(&installed),
    );
    assert!(
        text(&link).contains(&format!("{}.debug", library_version())),
        "{}",
        text(&link)
    );
    // Every C API function of the header is still exported.
    let nm = run_ok(
        Command::new("nm")
            .args(["-D", "--defined-only"])
            .arg(&installed),
    );
    let exported = text(&nm);
    let header = std::fs::read_to_string(root().join("include/jointlin.h")).unwrap();
    let functions: Vec<&str> = header
        .lines()
        .filter(|l| l.starts_with(|c: char| c.is_ascii_alphabetic()))
        .filter_map(|l| l.split_once('(')?.0.split_whitespace().last())
        .map(|name| name.trim_start_matches('*'))
        .filter(|name| name.starts_with("jointlin_"))
        .collect();
    assert!(functions.len() >= 20, "{functions:?}");
    for name in functions {
        assert!(
            exported.lines().any(|l| l.ends_with(&format!(" T {name}"))),
            "{name} not exported by the installed library"
        );
    }
}

/// The shim's build from the installed share directory with other flags (gfortran here;
/// ifort/ifx take the same variables): `make -C <prefix>/share/jointlin/fortran-shim`
/// with the installed library as the default JOINTLIN_LIBDIR; its shim_check runs
/// against the installed library.
#[test]
fn installed_shim_rebuilds_from_the_share_directory_with_other_flags() {
    let p = prefix();
    let build = scratch("shim-rebuild");
    run_ok(
        Command::new("make")
            .arg("-s")
            .arg("-C")
            .arg(p.join("share/jointlin/fortran-shim"))
            .arg(format!("BUILD={}", build.display()))
            .arg("FC=gfortran")
            .arg("FFLAGS=-O0 -fPIC -fcheck=all -finit-real=snan -finit-integer=-77777")
            .arg("MODFLAG=-J"),
    );
    for f in [
        "libjointlin_abaqus.a",
        "jointlin.mod",
        "jointlin_abaqus.mod",
        "shim_check",
    ] {
        assert!(build.join(f).is_file(), "{f} not built");
    }
    let exe = build.join("shim_check");
    let d = dynamic(&exe);
    assert!(
        d.contains(&format!("Shared library: [{}]", soname())),
        "{d}"
    );
    assert!(d.contains(&p.join("lib").display().to_string()), "{d}");
    let out = run_ok(Command::new(&exe).current_dir(&build));
    let stdout = text(&out);
    let fields: Vec<&str> = stdout.split_whitespace().collect();
    assert_eq!(fields.first(), Some(&"shim_check"), "{fields:?}");
    // p = k_N h = 1e4 * 2e-4 (linear normal law, AREA = 1), the contact closed.
    let pressure: f64 = fields[1].parse().unwrap();
    assert!((pressure - 2.0).abs() < 1e-12, "{fields:?}");
    // The MPI variant builds from the installed sources too, where an MPI compiler is.
    if Command::new("mpif90")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
    {
        let mpi = scratch("shim-rebuild-mpi");
        run_ok(
            Command::new("make")
                .arg("-s")
                .arg("-C")
                .arg(p.join("share/jointlin/fortran-shim"))
                .arg(format!("BUILD={}", mpi.display()))
                .arg("FC=mpif90")
                .arg("MPI=yes"),
        );
        assert!(mpi.join("libjointlin_abaqus.a").is_file());
        let nm = run_ok(Command::new("nm").arg(mpi.join("libjointlin_abaqus.a")));
        assert!(text(&nm).contains(" U mpi_allreduce_"), "{}", text(&nm));
    } else {
        tools::missing(
            "hosts_install_mpi_shim",
            "mpif90",
            "the MPI build of the installed shim",
        );
    }
}

fn pkg_config(prefix: &Path) -> Vec<String> {
    let out = run_ok(
        Command::new("pkg-config")
            .args(["--cflags", "--libs", "jointlin"])
            .env("PKG_CONFIG_PATH", prefix.join("lib/pkgconfig")),
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .split_whitespace()
        .map(str::to_string)
        .collect()
}

/// "k* = <v> N/mm, d* = <v> N s/mm" -> (k*, d*), compared with the Rust API to the 6
/// printed digits.
fn check_hello(stdout: &[u8], what: &str) {
    let text = String::from_utf8_lossy(stdout);
    let nums: Vec<f64> = text
        .split(|c: char| c.is_whitespace() || c == ',')
        .filter_map(|w| w.parse().ok())
        .collect();
    let c = Contact {
        law: TangentialLaw::Mindlin,
        rule: Rule::Thesis,
        mu: 0.3,
        normal_force: 2.0,
        k_t0: 1282.7,
    };
    let l = linearize(&c, 4.401e-4, 1.3, Method::default()).unwrap();
    assert_eq!(nums.len(), 2, "{what}: {text}");
    for (got, want) in nums.iter().zip([l.k_star, l.d_star]) {
        assert!((got - want).abs() <= 5e-6 * want, "{what}: {got} vs {want}");
    }
}

/// A program built against the install loads the library by its SONAME from the
/// pkg-config rpath.
fn check_loads_installed(exe: &Path) {
    let d = dynamic(exe);
    assert!(
        d.contains(&format!("Shared library: [{}]", soname())),
        "{d}"
    );
    assert!(
        d.contains(&prefix().join("lib").display().to_string()),
        "{d}"
    );
}

#[test]
fn c_example_builds_with_pkg_config_against_the_install() {
    let p = prefix();
    let dir = scratch("hello-c");
    let exe = dir.join("hello");
    run_ok(
        Command::new("gcc")
            .args(["-std=c99", "-Wall", "-Werror", "-o"])
            .arg(&exe)
            .arg(root().join("examples/c/hello.c"))
            .args(pkg_config(p)),
    );
    check_loads_installed(&exe);
    check_hello(&run_ok(&mut Command::new(&exe)).stdout, "C example");
}

#[test]
fn fortran_example_builds_with_pkg_config_against_the_install() {
    let p = prefix();
    let dir = scratch("hello-f");
    let exe = dir.join("hello");
    run_ok(
        Command::new("gfortran")
            .args(["-Wall", "-o"])
            .arg(&exe)
            .arg(root().join("examples/fortran/hello.f90"))
            .args(pkg_config(p))
            .current_dir(&dir),
    );
    check_loads_installed(&exe);
    check_hello(&run_ok(&mut Command::new(&exe)).stdout, "Fortran example");
}

/// link_sl of the installed examples/abaqus/abaqus_v6.env evaluated as Abaqus would
/// (Python, on top of an empty list): `make install` wrote the prefix into it.
fn link_sl(prefix: &Path) -> Vec<String> {
    let installed = prefix.join("share/jointlin/examples/abaqus/abaqus_v6.env");
    let env = std::fs::read_to_string(installed).unwrap();
    assert!(
        !env.contains("/opt/jointlin")
            && env.contains(&format!("jointlin = '{}'", prefix.display())),
        "{env}"
    );
    let script = format!("link_sl = []\n{env}\nprint('\\n'.join(link_sl))\n");
    let out = run_ok(Command::new("python3").arg("-c").arg(script));
    text(&out).lines().map(str::to_string).collect()
}

#[test]
fn abaqus_user_library_links_and_loads_with_the_env_file_alone() {
    let p = prefix();
    let dir = scratch("abaqus");
    // The job's user subroutine file (examples/abaqus/user.f: none of jointlin's names),
    // compiled as Abaqus compiles it, then linked by gcc: only link_sl brings jointlin and
    // the Fortran runtime.
    run_ok(
        Command::new("gfortran")
            .args(["-c", "-fPIC", "-o"])
            .arg(dir.join("user.o"))
            .arg(root().join("examples/abaqus/user.f")),
    );
    let lib = dir.join("libstandardU.so");
    run_ok(
        Command::new("gcc")
            .args(["-shared", "-fPIC", "-o"])
            .arg(&lib)
            .arg(dir.join("user.o"))
            .args(link_sl(p)),
    );
    let nm = run_ok(Command::new("nm").arg("-D").arg("--defined-only").arg(&lib));
    let symbols = text(&nm);
    for s in ["uinter_", "uexternaldb_", "urdfil_"] {
        assert!(
            symbols.lines().any(|l| l.ends_with(&format!(" T {s}"))),
            "{s} not in the user library:\n{symbols}"
        );
    }
    let d = dynamic(&lib);
    assert!(d.contains(&format!("[{}]", soname())), "{d}");
    assert!(d.contains("[libgfortran.so.5]"), "{d}");
    assert!(d.contains(&p.join("lib").display().to_string()), "{d}");
    // Loaded as Abaqus loads it: all symbols now (RTLD_NOW), utility routines from the
    // executable.
    let loader = dir.join("abaqus_loader");
    run_ok(
        Command::new("gcc")
            .args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-rdynamic", "-o"])
            .arg(&loader)
            .arg(root().join("harness/c/abaqus_loader.c"))
            .arg("-ldl"),
    );
    assert!(!dynamic(&loader).contains("gfortran"));
    let out = run_ok(Command::new(&loader).arg(&lib).current_dir(&dir));
    let fields: Vec<String> = text(&out).split_whitespace().map(str::to_string).collect();
    assert_eq!(
        fields.first().map(String::as_str),
        Some("loader"),
        "{fields:?}"
    );
    let pressure: f64 = fields[1].parse().unwrap();
    assert!((pressure - 2.0).abs() < 1e-12, "{fields:?}");
    assert_eq!(fields[3], "1", "contact closed: {fields:?}");
    // Without the runtime line the same link leaves _gfortran_* unresolved and the
    // loader fails: the line is needed, not decoration.
    let bare: Vec<String> = link_sl(p)
        .into_iter()
        .filter(|a| !a.contains("gfortran"))
        .collect();
    let lib2 = dir.join("libstandardU-bare.so");
    run_ok(
        Command::new("gcc")
            .args(["-shared", "-fPIC", "-o"])
            .arg(&lib2)
            .arg(dir.join("user.o"))
            .args(&bare),
    );
    let out = Command::new(&loader).arg(&lib2).output().unwrap();
    assert!(!out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("_gfortran_"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn the_guides_carry_the_examples_verbatim() {
    for (doc, file, lang) in [
        ("docs/c-fortran.md", "examples/c/hello.c", "c"),
        ("docs/c-fortran.md", "examples/fortran/hello.f90", "fortran"),
        ("docs/abaqus.md", "examples/abaqus/abaqus_v6.env", "python"),
        (
            "docs/abaqus.md",
            "examples/abaqus/block-on-plane/jointlin.cfg",
            "ini",
        ),
        ("docs/abaqus.md", "examples/abaqus/user.f", "fortran"),
    ] {
        let text = std::fs::read_to_string(root().join(doc)).unwrap();
        let body = std::fs::read_to_string(root().join(file)).unwrap();
        let block = format!("```{lang}\n{body}```\n");
        assert!(
            text.contains(&block),
            "{doc} lacks {file} verbatim in a ```{lang} block"
        );
    }
}
