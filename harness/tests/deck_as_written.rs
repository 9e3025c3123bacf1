//! Decks as users write them are read exactly as Abaqus reads them, or refused with
//! `file:line: *KEYWORD[, PARAMETER=]: message` and exit code 2: node sets from element
//! sets, parameters the reader does not implement, cylindrical nodes, repeated faces
//! and pair lines, tolerances judged on the paired faces, logarithmic sweeps from 0 Hz,
//! include bombs. Each test writes the deck as a user would and compares the run with
//! the same model written plainly.

use std::path::{Path, PathBuf};
use std::process::Command;

use jointlin_harness::validate::stack_deck::{stack_deck, Joining};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-as-written-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `jointlin ARGS`: exit code and stderr.
fn jointlin(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs deck text `text` as `d/name.inp`: exit code, stderr and results.csv's numbers
/// (status column left out; empty when the run failed).
fn run(d: &Path, name: &str, text: &str) -> (i32, String, Vec<Vec<f64>>) {
    let deck = d.join(format!("{name}.inp"));
    std::fs::write(&deck, text).unwrap();
    let out = d.join(format!("{name}-out"));
    let (code, log) = jointlin(&[
        "run",
        deck.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--no-plots",
    ]);
    let rows = std::fs::read_to_string(out.join("results.csv"))
        .map(|t| {
            let mut lines = t.lines();
            let header: Vec<&str> = lines.next().unwrap().split(',').collect();
            let status = header.iter().position(|h| *h == "status");
            lines
                .map(|l| {
                    l.split(',')
                        .enumerate()
                        .filter(|&(i, _)| Some(i) != status)
                        .map(|(_, v)| v.parse().unwrap())
                        .collect()
                })
                .collect()
        })
        .unwrap_or_default();
    (code, log, rows)
}

/// Asserts both runs succeeded with the same numbers within `rtol`, and not all zero.
fn same(a: &(i32, String, Vec<Vec<f64>>), b: &(i32, String, Vec<Vec<f64>>), rtol: f64) {
    assert_eq!(a.0, 0, "{}", a.1);
    assert_eq!(b.0, 0, "{}", b.1);
    assert_eq!(a.2.len(), b.2.len());
    assert!(!a.2.is_empty());
    let scale = a.2.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    for (x, y) in a.2.iter().flatten().zip(b.2.iter().flatten()) {
        assert!(
            (x - y).abs() <= rtol * x.abs().max(1e-12 * scale),
            "{x} vs {y}"
        );
    }
    // The response itself (the columns after the frequency) is not zero.
    assert!(
        a.2.iter().any(|r| r[1..].iter().any(|v| *v != 0.0)),
        "zero response"
    );
}

/// Asserts a refused run: exit code 2, and `needle` in its message.
fn refused(r: &(i32, String, Vec<Vec<f64>>), needle: &str) {
    assert_eq!(r.0, 2, "exit code {}: {}", r.0, r.1);
    assert!(r.1.contains(needle), "`{needle}` not in: {}", r.1);
}

/// A steel block 10 × 2 × 2 mm of 5 × 1 × 1 C3D8 elements, clamped at x = 0, pushed in z
/// at its free end by the nodes of `load` (a node set the caller defines in `sets`),
/// swept linearly over 1000…5000 Hz in 5 points. Nodes are `id, x, y, z` unless
/// `node_lines` writes them.
fn block(sets: &str, load: &str, node_lines: &dyn Fn(u64, [f64; 3]) -> String) -> String {
    let (nx, ny, nz) = (5usize, 1usize, 1usize);
    let id = |i: usize, j: usize, k: usize| (1 + i + (nx + 1) * (j + (ny + 1) * k)) as u64;
    let mut s =
        String::from("*HEADING\nsteel block\n** jointlin units: length=mm force=N time=s mass=t\n");
    s.push_str(&node_header());
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let x = [2.0 * i as f64, 2.0 * j as f64, 2.0 * k as f64];
                s.push_str(&node_lines(id(i, j, k), x));
            }
        }
    }
    s.push_str("*ELEMENT, TYPE=C3D8, ELSET=BLOCK\n");
    for i in 0..nx {
        let n = [
            id(i, 0, 0),
            id(i + 1, 0, 0),
            id(i + 1, 1, 0),
            id(i, 1, 0),
            id(i, 0, 1),
            id(i + 1, 0, 1),
            id(i + 1, 1, 1),
            id(i, 1, 1),
        ];
        let n: Vec<String> = n.iter().map(u64::to_string).collect();
        s.push_str(&format!("{}, {}\n", i + 1, n.join(", ")));
    }
    let clamp: Vec<String> = (0..=nz)
        .flat_map(|k| (0..=ny).map(move |j| id(0, j, k).to_string()))
        .collect();
    s.push_str(&format!(
        "*NSET, NSET=CLAMP\n{}\n*NSET, NSET=OUT\n{}\n{sets}",
        clamp.join(", "),
        id(nx, 0, nz)
    ));
    s.push_str("*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n*DENSITY\n7.85e-9\n*DAMPING, ALPHA=0., BETA=1e-7\n*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL\n,\n*BOUNDARY\nCLAMP, ENCASTRE\n");
    s.push_str(&format!("*STEP, NAME=SWEEP, PERTURBATION\n*STEADY STATE DYNAMICS, DIRECT, FREQUENCY SCALE=LINEAR\n1000., 5000., 5\n*CLOAD\n{load}, 3, 0.25\n*NODE PRINT, NSET=OUT\nU\n*END STEP\n"));
    s
}

fn node_header() -> String {
    "*NODE\n".into()
}

fn cartesian(id: u64, x: [f64; 3]) -> String {
    format!("{id}, {:?}, {:?}, {:?}\n", x[0], x[1], x[2])
}

/// The nodes of the block's last element (x = 8…10 mm).
const TIP_NODES: &str = "5, 6, 11, 12, 17, 18, 23, 24";

/// The block loaded on its last element's nodes, listed by number (set TIPN).
fn plain_block() -> String {
    block(
        &format!("*NSET, NSET=TIPN\n{TIP_NODES}\n"),
        "TIPN",
        &cartesian,
    )
}

#[test]
fn a_node_set_from_an_element_set_holds_that_elements_nodes() {
    let d = dir("nset-elset");
    let plain = run(&d, "plain", &plain_block());
    let from_elset = run(
        &d,
        "elset",
        &block(
            "*ELSET, ELSET=TIPEL\n5\n*NSET, NSET=TIPN, ELSET=TIPEL\n",
            "TIPN",
            &cartesian,
        ),
    );
    same(&plain, &from_elset, 1e-12);
    // An empty set that a load uses is an error at the load's data line, not zero load.
    let empty = block("*NSET, NSET=TIPN\n", "TIPN", &cartesian);
    let line = empty
        .lines()
        .position(|l| l.starts_with("TIPN, 3"))
        .unwrap()
        + 1;
    refused(
        &run(&d, "empty", &empty),
        &format!("empty.inp:{line}: *CLOAD: node set TIPN is empty"),
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn parameters_and_fields_the_reader_does_not_implement_are_refused_at_their_line() {
    let d = dir("params");
    let base = plain_block();
    let line_of =
        |text: &str, start: &str| text.lines().position(|l| l.starts_with(start)).unwrap() + 1;
    for (name, from, to, needle) in [
        (
            "composite",
            "*DAMPING, ALPHA=0., BETA=1e-7",
            "*DAMPING, COMPOSITE=0.02",
            "*DAMPING, COMPOSITE=: parameter not supported",
        ),
        (
            "velocity",
            "*BOUNDARY\n",
            "*BOUNDARY, TYPE=VELOCITY\n",
            "*BOUNDARY, TYPE=: TYPE=VELOCITY",
        ),
        (
            "unknown",
            "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
            "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL, ORIENTATION=ORI",
            "*SOLID SECTION, ORIENTATION=: parameter not supported",
        ),
        (
            "temperature",
            "210000., 0.3\n",
            "210000., 0.3, 20.\n",
            "*ELASTIC: 3 fields on a data line",
        ),
        (
            "op-new",
            "*CLOAD\n",
            "*CLOAD, OP=NEW\n",
            "*CLOAD, OP=: OP=NEW",
        ),
    ] {
        let text = base.replacen(from, to, 1);
        assert_ne!(text, base, "{name}");
        let at = if name == "temperature" {
            line_of(&text, "210000.")
        } else {
            line_of(&text, to.trim_end())
        };
        refused(&run(&d, name, &text), &format!("{name}.inp:{at}: {needle}"));
    }
    // *NODE, INPUT= reads the nodes from that file: the same model as inline.
    let inline = base.clone();
    let (head, rest) = inline.split_once("*NODE\n").unwrap();
    let (nodes, tail) = rest.split_once("*ELEMENT").unwrap();
    std::fs::write(
        d.join("nodes.txt"),
        format!("** the block's nodes\n{nodes}"),
    )
    .unwrap();
    let from_file = format!("{head}*NODE, INPUT=nodes.txt\n*ELEMENT{tail}");
    same(
        &run(&d, "inline", &inline),
        &run(&d, "input", &from_file),
        1e-12,
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn cylindrical_and_spherical_nodes_are_placed_as_abaqus_places_them() {
    let d = dir("system");
    let sets = format!("*NSET, NSET=TIPN\n{TIP_NODES}\n");
    let plain = run(&d, "plain", &block(&sets, "TIPN", &cartesian));
    // Each node as (r, θ°, z) about the z axis.
    let cyl = block(&sets, "TIPN", &|id, x| {
        let r = x[0].hypot(x[1]);
        let t = x[1].atan2(x[0]).to_degrees();
        format!("{id}, {r:?}, {t:?}, {:?}\n", x[2])
    })
    .replace("*NODE\n", "*NODE, SYSTEM=C\n");
    same(&plain, &run(&d, "cyl", &cyl), 1e-9);
    // (r, θ°, φ°): φ from the x–y plane toward z.
    let sph = block(&sets, "TIPN", &|id, x| {
        let r = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
        let t = x[1].atan2(x[0]).to_degrees();
        let p = x[2].atan2(x[0].hypot(x[1])).to_degrees();
        format!("{id}, {r:?}, {t:?}, {p:?}\n")
    })
    .replace("*NODE\n", "*NODE, SYSTEM=S\n");
    same(&plain, &run(&d, "sph", &sph), 1e-9);
    let _ = std::fs::remove_dir_all(&d);
}

/// The stack with a Jenkins contact, two frequencies below its first resonance.
fn contact_stack() -> String {
    let joint = Joining::Contact {
        mu: 0.3,
        k_t0: 1e5,
        k_n: 1e6,
        pressure: 1.0,
    };
    stack_deck(joint, 2, Some((200.0, 400.0, 2)))
}

#[test]
fn repeated_faces_and_pair_lines_count_once_and_a_doubly_paired_node_is_refused() {
    let d = dir("repeats");
    let base = contact_stack();
    let plain = run(&d, "plain", &base);
    // A face listed twice in the surface the preload presses.
    let twice = base.replacen(
        "*SURFACE, NAME=L3-TOP, TYPE=ELEMENT\nL3, S2",
        "*SURFACE, NAME=L3-TOP, TYPE=ELEMENT\nL3, S2\nL3, S2",
        1,
    );
    assert_ne!(twice, base);
    let r = run(&d, "face-twice", &twice);
    same(&plain, &r, 1e-12);
    // The same pair line twice.
    let pair = "*CONTACT PAIR, INTERACTION=JOINT, SMALL SLIDING\nL2-BOT, L1-TOP";
    let doubled = base.replacen(pair, &format!("{pair}\nL2-BOT, L1-TOP"), 1);
    assert_ne!(doubled, base);
    same(&plain, &run(&d, "pair-twice", &doubled), 1e-12);
    // Two slave surfaces sharing the layer's elements, paired with one master.
    let line = base.lines().position(|l| l == "L2-BOT, L1-TOP").unwrap() + 1;
    let shared = base.replacen(
        pair,
        "*SURFACE, NAME=L2-BOT-AGAIN, TYPE=ELEMENT\nL2, S1\n*CONTACT PAIR, INTERACTION=JOINT, SMALL SLIDING\nL2-BOT, L1-TOP\nL2-BOT-AGAIN, L1-TOP",
        1,
    );
    let r = run(&d, "shared", &shared);
    refused(
        &r,
        &format!("shared.inp:{}: *CONTACT PAIR: slave node ", line + 3),
    );
    refused(
        &r,
        &format!(
            "is in L2-BOT-AGAIN/L1-TOP and in L2-BOT/L1-TOP (line {})",
            line + 2
        ),
    );
    // Slave and master the same surface.
    let same_surface = base.replacen("L2-BOT, L1-TOP", "L1-TOP, L1-TOP", 1);
    refused(
        &run(&d, "self", &same_surface),
        "slave and master are the same surface L1-TOP",
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Two C3D8 blocks 4 × 2 × 1 mm, the upper one `gap` mm above the lower, the upper's
/// bottom joined to the lower's top by `joint` (`*TIE …` or `*CONTACT PAIR …` with its
/// cards), and a reference node far away at x = 1e6 mm, clamped.
fn gapped(gap: f64, joint: &str) -> String {
    let mut s = String::from(
        "*HEADING\ntwo blocks\n** jointlin units: length=mm force=N time=s mass=t\n*NODE\n",
    );
    let mut id = 0;
    for (b, z0) in [(0, 0.0), (1, 1.0 + gap)] {
        for k in 0..2 {
            for j in 0..2 {
                for i in 0..3 {
                    id += 1;
                    let _ = b;
                    s.push_str(&format!(
                        "{id}, {}, {}, {}\n",
                        2.0 * i as f64,
                        2.0 * j as f64,
                        z0 + k as f64
                    ));
                }
            }
        }
    }
    s.push_str("999, 1000000., 0., 0.\n");
    for (b, set) in [(0, "LOW"), (12, "UP")] {
        s.push_str(&format!("*ELEMENT, TYPE=C3D8, ELSET={set}\n"));
        for i in 0..2u64 {
            let n = |i: u64, j: u64, k: u64| b + 1 + i + 3 * j + 6 * k;
            s.push_str(&format!(
                "{}, {}, {}, {}, {}, {}, {}, {}, {}\n",
                b / 6 + i + 1,
                n(i, 0, 0),
                n(i + 1, 0, 0),
                n(i + 1, 1, 0),
                n(i, 1, 0),
                n(i, 0, 1),
                n(i + 1, 0, 1),
                n(i + 1, 1, 1),
                n(i, 1, 1)
            ));
        }
    }
    s.push_str("*SURFACE, NAME=LOW-TOP\nLOW, S2\n*SURFACE, NAME=UP-BOT\nUP, S1\n*NSET, NSET=CLAMP\n1, 4, 7, 10, 999\n*NSET, NSET=OUT\n18\n*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n*DENSITY\n7.85e-9\n*SOLID SECTION, ELSET=LOW, MATERIAL=STEEL\n*SOLID SECTION, ELSET=UP, MATERIAL=STEEL\n*BOUNDARY\nCLAMP, ENCASTRE\n");
    s.push_str(joint);
    s.push_str("*STEP\n*STEADY STATE DYNAMICS, DIRECT, FREQUENCY SCALE=LINEAR\n100., 200., 2\n*CLOAD\nOUT, 3, 1.\n*NODE PRINT, NSET=OUT\nU\n*END STEP\n");
    s
}

#[test]
fn tolerances_are_judged_on_the_paired_faces_not_on_a_far_reference_node() {
    let d = dir("tolerance");
    let tie = "*TIE, NAME=GLUE\nUP-BOT, LOW-TOP\n";
    // Touching: the tie merges the coincident nodes and runs.
    let (code, log, rows) = run(&d, "touching", &gapped(0.0, tie));
    assert_eq!(code, 0, "{log}");
    assert_eq!(rows.len(), 2);
    // 0.5 mm apart (a quarter of the faces' 2.8 mm diagonal): beyond the default
    // position tolerance (5 % of it), however far the reference node lies.
    let r = run(&d, "tie-gap", &gapped(0.5, tie));
    refused(&r, "*TIE: slave node ");
    refused(
        &r,
        "lies 5e-1 mm from master LOW-TOP, beyond the position tolerance 1.41",
    );
    // With POSITION TOLERANCE=1 it is tied across the gap, and the gap is reported.
    let (code, log, _) = run(
        &d,
        "tie-tolerance",
        &gapped(
            0.5,
            "*TIE, NAME=GLUE, POSITION TOLERANCE=1.\nUP-BOT, LOW-TOP\n",
        ),
    );
    assert_eq!(code, 0, "{log}");
    assert!(
        log.contains("6 slave nodes lie off the master surface, up to 5e-1 mm"),
        "{log}"
    );
    // A contact pair across the gap pairs nothing: refused, not run as touching.
    let contact = "*SURFACE INTERACTION, NAME=JOINT, USER, PROPERTIES=7\n1.\n1, 0, 0.3, 1e5, 0, 1e6, 0\n*CONTACT PAIR, INTERACTION=JOINT\nUP-BOT, LOW-TOP\n";
    refused(
        &run(&d, "pair-gap", &gapped(0.5, contact)),
        "do not overlap",
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_logarithmic_sweep_from_zero_is_refused_at_its_line() {
    let d = dir("log");
    let base = plain_block();
    let text = base
        .replace(", FREQUENCY SCALE=LINEAR", "")
        .replace("1000., 5000., 5", "0., 5000., 5");
    let line = text.lines().position(|l| l == "0., 5000., 5").unwrap() + 1;
    refused(
        &run(&d, "zero", &text),
        &format!("zero.inp:{line}: *STEADY STATE DYNAMICS: f_low = 0 on a logarithmic scale"),
    );
    let huge = base.replace("1000., 5000., 5", "1e-300, 1e300, 5");
    refused(&run(&d, "huge", &huge), "above 1e150 (1/time)");
    // A wide logarithmic sweep within range runs with finite frequencies.
    let wide = base
        .replace(", FREQUENCY SCALE=LINEAR", "")
        .replace("1000., 5000., 5", "1e-100, 1e100, 3");
    let (code, log, rows) = run(&d, "wide", &wide);
    assert_eq!(code, 0, "{log}");
    let f: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    assert_eq!(f.len(), 3);
    for (a, b) in f.iter().zip([1e-100, 1.0, 1e100]) {
        assert!((a / b - 1.0).abs() < 1e-9, "{f:?}");
    }
    assert!(rows.iter().flatten().all(|v| v.is_finite()), "{rows:?}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn includes_that_multiply_and_endless_files_stop_with_a_named_error() {
    let d = dir("include");
    // 14 files, each including the next four times: 4^13 reads if nothing stopped it.
    for i in 0..14 {
        let body = if i == 13 {
            "** leaf\n".to_string()
        } else {
            format!("*INCLUDE, INPUT=f{}.inp\n", i + 1).repeat(4)
        };
        std::fs::write(d.join(format!("f{i}.inp")), body).unwrap();
    }
    let t = std::time::Instant::now();
    let (code, log) = jointlin(&["check", d.join("f0.inp").to_str().unwrap()]);
    assert_eq!(code, 2, "{log}");
    assert!(
        log.contains("more than 10000 files read for one deck"),
        "{log}"
    );
    assert!(t.elapsed().as_secs() < 60, "{:?}", t.elapsed());
    // A device that never ends.
    std::fs::write(
        d.join("zero.inp"),
        "*HEADING\nx\n*INCLUDE, INPUT=/dev/zero\n",
    )
    .unwrap();
    let (code, log) = jointlin(&["check", d.join("zero.inp").to_str().unwrap()]);
    assert_eq!(code, 2, "{log}");
    assert!(
        log.contains("zero.inp:3: *INCLUDE: /dev/zero: the deck and its files exceed 1024 MiB"),
        "{log}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn the_documented_keyword_table_is_the_one_the_reader_checks_against() {
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["check", "--keywords"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let table = String::from_utf8(out.stdout).unwrap();
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/own-model.md"))
        .unwrap();
    let block = doc
        .split("<!-- BEGIN deck_keywords -->\n")
        .nth(1)
        .and_then(|b| b.split("<!-- END deck_keywords -->").next())
        .unwrap();
    assert!(
        block.ends_with(&table),
        "docs/own-model.md's deck_keywords block is stale: bash scripts/readme-tables.sh deck_keywords"
    );
    assert!(table.contains("| `*DAMPING` | `ALPHA=`"), "{table}");
}

#[test]
fn a_node_in_no_element_is_dropped_with_a_note_and_a_load_on_it_refused() {
    let d = dir("orphan");
    let base = plain_block();
    let orphan = base.replacen(
        "*ELEMENT, TYPE=C3D8",
        "500, 50., 50., 50.\n*ELEMENT, TYPE=C3D8",
        1,
    );
    assert_ne!(orphan, base);
    let r = run(&d, "orphan", &orphan);
    same(&run(&d, "plain", &base), &r, 1e-12);
    assert!(
        r.1.contains("1 nodes in no element (500): dropped"),
        "{}",
        r.1
    );
    let loaded = orphan.replace("*NSET, NSET=TIPN\n", "*NSET, NSET=TIPN\n500, ");
    refused(
        &run(&d, "loaded", &loaded),
        "*CLOAD: node 500 is in no element: the load would act on nothing",
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_deck_too_large_for_the_machine_is_refused_by_check_and_run_before_it_is_built() {
    let d = dir("size");
    let base = plain_block();
    // 300 lines of 1e7 frequencies each: refused at the line that passes 1e7 in all.
    let many = base.replace("1000., 5000., 5\n", &"1., 100., 10000000\n".repeat(300));
    let deck = d.join("many.inp");
    std::fs::write(&deck, &many).unwrap();
    let line = many
        .lines()
        .position(|l| l == "1., 100., 10000000")
        .unwrap()
        + 2;
    for cmd in ["check", "run"] {
        let o = d.join("o");
        let args: &[&str] = if cmd == "run" {
            &["run", deck.to_str().unwrap(), "--out", o.to_str().unwrap()]
        } else {
            &["check", deck.to_str().unwrap()]
        };
        let (code, log) = jointlin(args);
        assert_eq!(code, 2, "{cmd}: {log}");
        assert!(
            log.contains(&format!("many.inp:{line}: *STEADY STATE DYNAMICS: more than 10000000 frequencies in one step")),
            "{cmd}: {log}"
        );
    }
    // The mesh against a memory limit: named by check and by run, nothing written.
    let small = d.join("small.inp");
    std::fs::write(&small, &base).unwrap();
    for cmd in ["check", "run"] {
        let o = d.join("o");
        let mut args = vec![cmd, small.to_str().unwrap()];
        if cmd == "run" {
            args.extend(["--out", o.to_str().unwrap()]);
        }
        let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
            .env("JOINTLIN_MAX_MEMORY", "1M")
            .args(&args)
            .output()
            .unwrap();
        let log = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{cmd}: {log}");
        assert!(
            log.contains("*ELEMENT: the run needs about"),
            "{cmd}: {log}"
        );
        assert!(log.contains("24 nodes: 72 DOFs"), "{cmd}: {log}");
        assert!(
            log.contains("allowed by JOINTLIN_MAX_MEMORY"),
            "{cmd}: {log}"
        );
    }
    assert!(!d.join("o").join("results.csv").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_model_that_is_not_held_is_named_before_any_solve() {
    let d = dir("free");
    let base = plain_block();
    let free = base.replace("*BOUNDARY\nCLAMP, ENCASTRE\n", "");
    assert_ne!(free, base);
    refused(
        &run(&d, "free", &free),
        "*BOUNDARY: the model is not held: 6 rigid-body modes in the part of 24 nodes",
    );
    // Rotations only (solid nodes have none): as free.
    let rotations = base.replace("CLAMP, ENCASTRE", "CLAMP, 4, 6");
    refused(
        &run(&d, "rotations", &rotations),
        "the model is not held: 6 rigid-body modes",
    );
    // One node pinned: the three rotations about it stay.
    let pinned = base.replace("CLAMP, ENCASTRE", "1, PINNED");
    refused(
        &run(&d, "pinned", &pinned),
        "the model is not held: 3 rigid-body modes",
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn overflowing_materials_and_loads_and_empty_units_are_named_at_their_line() {
    let d = dir("magnitudes");
    let base = plain_block();
    let line_of =
        |text: &str, start: &str| text.lines().position(|l| l.starts_with(start)).unwrap() + 1;
    let huge_e = base.replace("210000., 0.3", "1e250, 0.3");
    refused(
        &run(&d, "e", &huge_e),
        &format!(
            "e.inp:{}: *MATERIAL: material STEEL: E = 1e250",
            line_of(&huge_e, "*MATERIAL")
        ),
    );
    let huge_f = base.replace("TIPN, 3, 0.25", "TIPN, 3, 1e300");
    refused(
        &run(&d, "f", &huge_f),
        &format!(
            "f.inp:{}: *CLOAD: force 1e300 beyond 1e150",
            line_of(&huge_f, "*CLOAD")
        ),
    );
    let empty = base.replace("length=mm", "length=");
    refused(
        &run(&d, "units", &empty),
        "units.inp:3: **: `length=`: the unit of length is empty",
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn what_abaqus_cae_writes_is_read_and_included_data_lines_are_named_in_their_file() {
    let d = dir("cae");
    let base = plain_block();
    let plain = run(&d, "plain", &base);
    // CAE's parameters that change nothing a run computes.
    let cae = base.replace(
        "*STEADY STATE DYNAMICS, DIRECT, FREQUENCY SCALE=LINEAR",
        "*Steady State Dynamics, direct, friction damping=NO, frequency scale=LINEAR",
    );
    let cae = cae.replace(
        "*STEP, NAME=SWEEP, PERTURBATION\n",
        "*STEP, NAME=MODES, PERTURBATION\n*Frequency, eigensolver=Lanczos, sim=NO, acoustic coupling=on, normalization=displacement\n3, , , , ,\n*END STEP\n*STEP, NAME=SWEEP, PERTURBATION\n",
    );
    same(&plain, &run(&d, "cae", &cae), 1e-12);
    // A blank line after a card whose data lines come from its INPUT= file.
    let (head, rest) = base.split_once("*NODE\n").unwrap();
    let (nodes, tail) = rest.split_once("*ELEMENT").unwrap();
    std::fs::write(d.join("nodes.txt"), nodes).unwrap();
    let blank = format!("{head}*NODE, INPUT=nodes.txt\n\n*ELEMENT{tail}");
    same(&plain, &run(&d, "blank", &blank), 1e-12);
    // A frequency list in an included file: its bad line is named in that file.
    std::fs::write(d.join("sweep.frq"), "1000., 5000., 5\n0., 5000., 5\n").unwrap();
    let included = base
        .replace(", FREQUENCY SCALE=LINEAR", "")
        .replace("1000., 5000., 5\n", "*INCLUDE, INPUT=sweep.frq\n");
    let r = run(&d, "included", &included);
    refused(
        &r,
        "sweep.frq:2: *STEADY STATE DYNAMICS: f_low = 0 on a logarithmic scale",
    );
    // TYPE=SURFACE TO SURFACE: read where the tie conforms, refused where it does not.
    let s2s = "*TIE, NAME=GLUE, TYPE=SURFACE TO SURFACE\nUP-BOT, LOW-TOP\n";
    let (code, log, _) = run(&d, "s2s", &gapped(0.0, s2s));
    assert_eq!(code, 0, "{log}");
    let s2s_far =
        "*TIE, NAME=GLUE, TYPE=SURFACE TO SURFACE, POSITION TOLERANCE=1.\nUP-BOT, LOW-TOP\n";
    refused(
        &run(&d, "s2s-gap", &gapped(0.5, s2s_far)),
        "*TIE, TYPE=: TYPE=SURFACE TO SURFACE on the non-conforming tie GLUE",
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Three steel beams 100 × 10 × 2 mm stacked in z, C3D8I with (x, y, z) cells `cells`
/// per layer (non-conforming), clamped together at x = 0, joined by contact pairs with
/// the USER interaction `law` (code, μ, k_T0 = k_N per area), pressed by 1 MPa on the
/// top face only.
fn pressed_beams(cells: [[usize; 3]; 3], law: (u8, f64, f64)) -> String {
    let (l, w, t) = (100.0, 10.0, 2.0);
    let mut s =
        String::from("*HEADING\nthree beams\n** jointlin units: length=mm force=N time=s mass=t\n");
    let (mut base, mut ebase, mut clamp, mut tip) = (0, 0, Vec::new(), 0);
    for (layer, [nx, ny, nz]) in cells.iter().copied().enumerate() {
        let id = |i: usize, j: usize, k: usize| base + 1 + i + (nx + 1) * (j + (ny + 1) * k);
        s.push_str("*NODE\n");
        for k in 0..=nz {
            for j in 0..=ny {
                for i in 0..=nx {
                    let x = [l * i as f64 / nx as f64, w * j as f64 / ny as f64];
                    let z = t * (layer as f64 + k as f64 / nz as f64);
                    s += &format!("{}, {:?}, {:?}, {z:?}\n", id(i, j, k), x[0], x[1]);
                    if i == 0 {
                        clamp.push(id(i, j, k).to_string());
                    }
                    if layer == 2 && i == nx && j == 0 && k == nz {
                        tip = id(i, j, k);
                    }
                }
            }
        }
        s += &format!("*ELEMENT, TYPE=C3D8I, ELSET=L{}\n", layer + 1);
        // Element numbers of the layer's bottom and top rows of cells.
        let (mut bottom, mut top) = (Vec::new(), Vec::new());
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    ebase += 1;
                    let n = [
                        id(i, j, k),
                        id(i + 1, j, k),
                        id(i + 1, j + 1, k),
                        id(i, j + 1, k),
                        id(i, j, k + 1),
                        id(i + 1, j, k + 1),
                        id(i + 1, j + 1, k + 1),
                        id(i, j + 1, k + 1),
                    ];
                    let n: Vec<String> = n.iter().map(usize::to_string).collect();
                    s += &format!("{ebase}, {}\n", n.join(", "));
                    if k == 0 {
                        bottom.push(ebase);
                    }
                    if k + 1 == nz {
                        top.push(ebase);
                    }
                }
            }
        }
        for (side, face, list) in [("BOT", "S1", bottom), ("TOP", "S2", top)] {
            s += &format!("*SURFACE, NAME=L{}-{side}\n", layer + 1);
            for e in list {
                s += &format!("{e}, {face}\n");
            }
        }
        base += (nx + 1) * (ny + 1) * (nz + 1);
    }
    let (code, mu, k) = law;
    s.push_str("*NSET, NSET=CLAMP\n");
    for chunk in clamp.chunks(16) {
        s += &format!("{}\n", chunk.join(", "));
    }
    s += &format!(
        "*NSET, NSET=TIP\n{tip}\n*ELSET, ELSET=ALL\nL1, L2, L3\n*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n*DENSITY\n7.85e-9\n*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL\n*BOUNDARY\nCLAMP, ENCASTRE\n\
         *SURFACE INTERACTION, NAME=JOINT, USER, PROPERTIES=7\n1.\n{code}, 0, {mu:e}, {k:e}, 0, {k:e}, 0\n\
         *CONTACT PAIR, INTERACTION=JOINT, SMALL SLIDING\nL2-BOT, L1-TOP\nL3-BOT, L2-TOP\n\
         *STEP\n*STATIC\n*DSLOAD\nL3-TOP, P, 1.\n*END STEP\n\
         *STEP, PERTURBATION\n*STEADY STATE DYNAMICS, DIRECT, FREQUENCY SCALE=LINEAR\n100., 200., 2\n*CLOAD\nTIP, 3, 1.\n*NODE PRINT, NSET=TIP\nU\n*END STEP\n"
    );
    s
}

#[test]
fn a_stuck_stack_pressed_from_one_side_finds_its_preload() {
    // Friction high enough to stick (μ = 1000, Mindlin) and an interface far stiffer
    // than the beams (k_T0 = k_N = 1e7 N/mm³), three beams of 10 × 2 × 2, 13 × 3 × 3 and
    // 16 × 2 × 2 cells: from rest, Newton's contact states cycle (points open and close
    // between iterations, 60 iterations are not enough); the preload is found by raising
    // the contact force gradually, and it is the model's own equilibrium (backward error
    // at round-off, every frequency converged).
    let d = dir("stuck");
    let deck = pressed_beams([[10, 2, 2], [13, 3, 3], [16, 2, 2]], (0, 1000.0, 1e7));
    let (iterations, stat) = stuck_run(&d, "stuck", &deck);
    assert!(
        iterations > 60,
        "{iterations}: Newton alone converged, the deck tests nothing"
    );
    equilibrium(&stat);
    // The interface 20× stiffer still (2e8 N/mm³, μ = 10, one cell thick): converged at
    // the residual's round-off floor (‖R‖ ≈ 1e-6 ‖f‖ there, 1e-13 of the terms it sums),
    // where a residual tolerance relative to the load alone stalled.
    let deck = pressed_beams([[6, 2, 1], [8, 2, 1], [10, 2, 1]], (0, 10.0, 2e8));
    let (_, stat) = stuck_run(&d, "stiffer", &deck);
    equilibrium(&stat);
    assert_eq!(stat["stopped_by"], "round-off floor");
    let _ = std::fs::remove_dir_all(&d);
}

/// Runs a stack deck; (static Newton iterations, run.json's static_step), every
/// frequency converged.
fn stuck_run(d: &Path, name: &str, deck: &str) -> (usize, serde_json::Value) {
    let r = run(d, name, deck);
    assert_eq!(r.0, 0, "{}", r.1);
    let json = std::fs::read_to_string(d.join(format!("{name}-out/run.json"))).unwrap();
    let json: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(json["all_converged"], true);
    let stat = json["static_step"].clone();
    (stat["newton_iterations"].as_u64().unwrap() as usize, stat)
}

/// The preload is an equilibrium: the residual within 1e-5 of the load (Abaqus's
/// default tolerance is 5e-3 of the average force) and at round-off of the terms it
/// sums.
fn equilibrium(stat: &serde_json::Value) {
    let relative = stat["relative_residual"].as_f64().unwrap();
    let backward = stat["backward_error"].as_f64().unwrap();
    assert!(relative <= 1e-5 && backward <= 1e-12, "{stat}");
}

#[test]
fn a_mode_based_step_needs_its_modes_and_modal_damping_a_mode_based_step() {
    use jointlin_harness::validate::matrices_ccx::{deck, tip_node};
    let d = dir("modal");
    let tip = tip_node();
    let check = |name: &str, step: &str| {
        let text = deck(&format!("*NSET, NSET=TIPN\n{tip}\n{step}"));
        let path = d.join(format!("{name}.inp"));
        std::fs::write(&path, &text).unwrap();
        let (code, log) = jointlin(&["check", path.to_str().unwrap()]);
        let line =
            move |needle: &str| text.lines().position(|l| l.starts_with(needle)).unwrap() + 1;
        (code, log, line)
    };
    let ssd = "*STEADY STATE DYNAMICS, FREQUENCY SCALE=LINEAR\n100., 900., 5\n";
    let load = "*CLOAD\nTIPN, 3, 1.\n*END STEP\n";
    // Without a *FREQUENCY step there are no modes to superpose.
    let (code, log, line) = check("no-modes", &format!("*STEP\n{ssd}{load}"));
    assert_eq!(code, 2, "{log}");
    let at = format!("no-modes.inp:{}: *STEADY STATE DYNAMICS", line("*STEP"));
    assert!(
        log.contains(&at) && log.contains("preceding *FREQUENCY"),
        "{log}"
    );
    // Modal damping in a DIRECT step would be ignored by Abaqus's direct solve: refused.
    let direct = "*STEADY STATE DYNAMICS, DIRECT, FREQUENCY SCALE=LINEAR\n100., 900., 5\n";
    let (code, log, line) = check(
        "direct-damped",
        &format!("*STEP\n{direct}*MODAL DAMPING\n1, 10, 0.02\n{load}"),
    );
    assert_eq!(code, 2, "{log}");
    let at = format!("direct-damped.inp:{}: *MODAL DAMPING", line("1, 10, 0.02"));
    assert!(log.contains(&at), "{log}");
    // A definition the reader does not implement is refused at its parameter.
    let modes = "*STEP\n*FREQUENCY\n6\n*END STEP\n";
    let (code, log, _) = check(
        "range",
        &format!("{modes}*STEP\n{ssd}*MODAL DAMPING, DEFINITION=FREQUENCY RANGE\n100., 900., 0.02\n{load}"),
    );
    assert_eq!(code, 2, "{log}");
    assert!(log.contains("*MODAL DAMPING, DEFINITION="), "{log}");
    // The complete mode-based deck checks.
    let (code, log, _) = check(
        "complete",
        &format!("{modes}*STEP\n{ssd}*MODAL DAMPING, RAYLEIGH\n,,100.,1e-6\n{load}"),
    );
    assert_eq!(code, 0, "{log}");
    let _ = std::fs::remove_dir_all(&d);
}
