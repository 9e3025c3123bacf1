//! `make install` into a temporary prefix, then the README's examples built against the
//! installed copy: C and Fortran with `pkg-config --cflags --libs jointlin`, Abaqus as a
//! user library linked with the `link_sl` addition of examples/abaqus/abaqus_v6.env. The
//! README must carry each example file verbatim.

mod hosts_common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use hosts_common::*;
use jointlin::hysteresis::Rule;
use jointlin::law::TangentialLaw;
use jointlin::linearize::{linearize, Contact, Method};

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
                .arg(format!("BUILD={}", dir.join("build").display())),
        );
        prefix
    })
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

#[test]
fn install_places_library_header_modules_and_pkg_config_file() {
    let p = prefix();
    for f in [
        "lib/libjointlin.so",
        "lib/libjointlin_abaqus.a",
        "lib/pkgconfig/jointlin.pc",
        "include/jointlin.h",
        "include/jointlin.mod",
        "include/jointlin_abaqus.mod",
        "share/jointlin/fortran-shim/uinter.f",
        "share/jointlin/fortran-shim/uexternaldb.f",
        "share/jointlin/fortran-shim/abaqus_standin.f",
    ] {
        assert!(p.join(f).is_file(), "{f} not installed");
    }
    let pc = std::fs::read_to_string(p.join("lib/pkgconfig/jointlin.pc")).unwrap();
    assert!(pc.contains(&format!("prefix={}", p.display())), "{pc}");
    assert!(pc.contains(&format!("Version: {}", env!("CARGO_PKG_VERSION"))));
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
    check_hello(&run_ok(&mut Command::new(&exe)).stdout, "Fortran example");
}

#[test]
fn abaqus_example_links_a_user_library_with_uinter_and_uexternaldb() {
    let p = prefix();
    let dir = scratch("abaqus");
    // abaqus_v6.env is Python: evaluate it as Abaqus would, on top of an empty link_sl,
    // with the install prefix in place of /opt/jointlin.
    let env = std::fs::read_to_string(root().join("examples/abaqus/abaqus_v6.env")).unwrap();
    let env = env.replace("/opt/jointlin", &p.display().to_string());
    let script = format!("link_sl = []\n{env}\nprint('\\n'.join(link_sl))\n");
    let out = run_ok(Command::new("python3").arg("-c").arg(script));
    let link_sl: Vec<String> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect();
    // The user's own subroutine file (here: none of jointlin's names), then link_sl.
    std::fs::write(
        dir.join("user.f"),
        "      SUBROUTINE USERSTUB\n      RETURN\n      END\n",
    )
    .unwrap();
    let lib = dir.join("libstandardU.so");
    run_ok(
        Command::new("gfortran")
            .args(["-shared", "-fPIC", "-o"])
            .arg(&lib)
            .arg(dir.join("user.f"))
            .args(&link_sl)
            .arg("-lgfortran"),
    );
    let nm = run_ok(Command::new("nm").arg("-D").arg("--defined-only").arg(&lib));
    let symbols = String::from_utf8_lossy(&nm.stdout);
    for s in ["uinter_", "uexternaldb_"] {
        assert!(
            symbols.lines().any(|l| l.ends_with(&format!(" T {s}"))),
            "{s} not in the user library:\n{symbols}"
        );
    }
    let elf = run_ok(Command::new("readelf").arg("-d").arg(&lib));
    let dynamic = String::from_utf8_lossy(&elf.stdout);
    assert!(dynamic.contains("[libjointlin.so]"), "{dynamic}");
    assert!(
        dynamic.contains(&p.join("lib").display().to_string()),
        "{dynamic}"
    );
}

#[test]
fn readme_carries_the_examples_verbatim() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    for (file, lang) in [
        ("examples/c/hello.c", "c"),
        ("examples/fortran/hello.f90", "fortran"),
        ("examples/abaqus/abaqus_v6.env", "python"),
        ("examples/abaqus/jointlin.cfg", "ini"),
        ("examples/abaqus/block.inp", "text"),
    ] {
        let body = std::fs::read_to_string(root().join(file)).unwrap();
        let block = format!("```{lang}\n{body}```\n");
        assert!(
            readme.contains(&block),
            "README.md lacks {file} verbatim in a ```{lang} block"
        );
    }
}
