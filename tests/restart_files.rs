//! Restart files a store did not write for this model and these settings: each is
//! JOINTLIN_ERR_IO at restore (LOP 4 or jointlin_store_restore), never a panic, and the
//! store keeps its state. Each case is a file that was once accepted or panicked
//! (docs/robustness.md, "Restart files").

mod ffi_common;

use ffi_common::*;
use jointlin::ffi::error::*;
use jointlin::ffi::store::*;
use jointlin::ffi::store_model::jointlin_store_set_model;
use std::path::{Path, PathBuf};

fn fresh_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "jointlin-restart-files-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A store saving to `path`, with relative tolerance `rtol` and model fingerprint `model`.
fn store_at(path: &Path, rtol: f64, model: &[u8]) -> *mut jointlin_store {
    let bytes = path.as_os_str().as_encoded_bytes();
    let mut cfg = unsafe { std::mem::zeroed::<jointlin_store_config>() };
    assert_eq!(unsafe { jointlin_store_config_default(&mut cfg) }, 0);
    cfg.initial_amplitude = 1e-4;
    cfg.rtol = rtol;
    cfg.restart_path = bytes.as_ptr().cast();
    cfg.restart_path_len = bytes.len();
    let mut store = std::ptr::null_mut();
    assert_eq!(unsafe { jointlin_store_new(&cfg, &mut store) }, 0);
    let status = unsafe { jointlin_store_set_model(store, model.as_ptr().cast(), model.len()) };
    assert_eq!(status, JOINTLIN_OK);
    store
}

/// Pass 1 over increments 1 and 2 with one point, restart data written at each LOP 2;
/// returns the file's text.
fn real_file(store: *const jointlin_store, path: &Path) -> String {
    assert_eq!(uexternaldb(store, 0, 0, 1, 0), 0);
    let mut id = 0i64;
    let name = b"BOLT-1";
    let coords = [1.0, 2.0, 0.5];
    let status = unsafe {
        jointlin_store_register_point(
            store,
            name.as_ptr().cast(),
            6,
            7,
            coords.as_ptr(),
            3,
            &mut id,
        )
    };
    assert_eq!(status, 0);
    for kinc in [1, 2] {
        assert_eq!(uexternaldb(store, 1, 0, 1, kinc), 0);
        let mut amp = [0.0; 2];
        assert_eq!(
            unsafe { jointlin_store_estimate(store, id, kinc, amp.as_mut_ptr()) },
            0
        );
        let back = [2e-4 * kinc as f64, 1e-4];
        assert_eq!(
            unsafe { jointlin_store_report(store, id, kinc, back.as_ptr()) },
            0
        );
        assert_eq!(uexternaldb(store, 2, 1, 1, kinc), 0);
    }
    std::fs::read_to_string(path).unwrap()
}

fn status_of(store: *const jointlin_store) -> (i32, jointlin_point_status, (i32, i32)) {
    let mut st = jointlin_point_status::default();
    let code = unsafe { jointlin_store_point_status(store, 1, 2, &mut st) };
    let mut action = (0, 0);
    assert_eq!(
        unsafe { jointlin_store_next_action(store, &mut action.0, &mut action.1) },
        JOINTLIN_OK
    );
    (code, st, action)
}

/// `text` (an edited restart file) with its checksum line written anew, so that a
/// restore reaches the checks behind the checksum.
fn resealed(text: &str) -> String {
    let body = text.rsplit_once("checksum ").map_or(text, |(b, _)| b);
    format!("{body}checksum {:08x}\n", crc32fast::hash(body.as_bytes()))
}

/// Writes `text` (resealed: [`resealed`]) to the restart path and restores:
/// JOINTLIN_ERR_IO, state unchanged.
fn rejected(store: *const jointlin_store, path: &Path, text: &str) {
    assert!(
        text.starts_with("jointlin-store"),
        "not a restart file: {text}"
    );
    let text = &resealed(text);
    let before = status_of(store);
    std::fs::write(path, text).unwrap();
    let status = unsafe { jointlin_store_restore(store) };
    assert_eq!(status, JOINTLIN_ERR_IO, "accepted:\n{text}");
    assert_eq!(uexternaldb(store, 4, 0, 1, 0), JOINTLIN_ERR_IO);
    assert_eq!(status_of(store), before, "changed by:\n{text}");
}

/// The `records` line of the point at increment `kinc` split into tokens.
fn record_line(text: &str, kinc: i32) -> (String, Vec<String>) {
    let line = text
        .lines()
        .find(|l| l.starts_with(&format!("1 {kinc} ")))
        .unwrap()
        .to_string();
    let tokens = line.split(' ').map(String::from).collect();
    (line, tokens)
}

#[test]
fn a_multi_byte_point_name_is_an_io_error_not_a_panic() {
    let dir = fresh_dir("utf8");
    let path = dir.join("store.restart");
    let store = store_at(&path, 1e-3, b"model A");
    let good = real_file(store, &path);
    // "x424f4c542d31" is BOLT-1: a two-byte character in the hex string panicked on a
    // character boundary (ERR_PANIC, a panic message on the host's stderr).
    for name in ["x42é4f4c542d", "xé", "x4é", "x424f4c542d3é"] {
        rejected(store, &path, &good.replace("x424f4c542d31", name));
    }
    unsafe { jointlin_store_free(store) };
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn nan_infinite_and_negative_amplitudes_are_rejected() {
    let dir = fresh_dir("values");
    let path = dir.join("store.restart");
    let store = store_at(&path, 1e-3, b"model A");
    let good = real_file(store, &path);
    let (line, tokens) = record_line(&good, 2);
    // Tokens: id, kinc, estimate pass, dirs, estimate ×2, reported pass, reported ×2, …,
    // then the history pairs.
    let bad_values = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -1e-4, -f64::MAX];
    for slot in [4usize, 5, 7, 8, tokens.len() - 1] {
        for v in bad_values {
            let mut t = tokens.clone();
            t[slot] = format!("{:016x}", v.to_bits());
            rejected(store, &path, &good.replace(&line, &t.join(" ")));
        }
    }
    // The good file restores, and the estimate is the stored one.
    std::fs::write(&path, &good).unwrap();
    assert_eq!(unsafe { jointlin_store_restore(store) }, JOINTLIN_OK);
    unsafe { jointlin_store_free(store) };
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_file_of_another_model_or_other_settings_is_rejected() {
    let dir = fresh_dir("model");
    let path = dir.join("store.restart");
    let writer = store_at(&path, 1e-3, b"model A");
    let good = real_file(writer, &path);
    // Another model (its file would schedule increments this sweep does not have).
    let other = store_at(&path, 1e-3, b"model B");
    rejected(other, &path, &good);
    // The same model with another tolerance.
    let loose = store_at(&path, 1e-2, b"model A");
    rejected(loose, &path, &good);
    // A store without a fingerprint does not take a fingerprinted file.
    let none = store_at(&path, 1e-3, b"");
    rejected(none, &path, &good);
    // The same model and settings restore.
    let same = store_at(&path, 1e-3, b"model A");
    std::fs::write(&path, &good).unwrap();
    assert_eq!(uexternaldb(same, 4, 0, 1, 0), JOINTLIN_OK);
    // Format 1 (no fingerprints): only a store without a model fingerprint reads it.
    let v1: String = good
        .replacen("jointlin-store 4", "jointlin-store 1", 1)
        .lines()
        .filter(|l| {
            !l.starts_with("model ") && !l.starts_with("settings ") && !l.starts_with("checksum ")
        })
        .map(|l| format!("{}\n", l.strip_suffix(" -").unwrap_or(l)))
        .collect();
    rejected(other, &path, &v1);
    // Formats 2 (fingerprints, no checksum) and 3 (no PROPS per point) are refused: a
    // one-byte edit of a format 4 file's version would otherwise make it one.
    let v2 = good
        .replacen("jointlin-store 4", "jointlin-store 2", 1)
        .replace(good.lines().last().unwrap(), "");
    std::fs::write(&path, &v2).unwrap();
    assert_eq!(unsafe { jointlin_store_restore(same) }, JOINTLIN_ERR_IO);
    std::fs::write(
        &path,
        resealed(&good.replacen("jointlin-store 4", "jointlin-store 3", 1)),
    )
    .unwrap();
    assert_eq!(unsafe { jointlin_store_restore(same) }, JOINTLIN_ERR_IO);
    std::fs::write(&path, &v1).unwrap();
    assert_eq!(unsafe { jointlin_store_restore(none) }, JOINTLIN_OK);
    for s in [writer, other, loose, none, same] {
        unsafe { jointlin_store_free(s) };
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn duplicate_keys_and_unknown_increments_are_rejected() {
    let dir = fresh_dir("duplicates");
    let path = dir.join("store.restart");
    let store = store_at(&path, 1e-3, b"model A");
    let good = real_file(store, &path);
    let point = good
        .lines()
        .find(|l| l.starts_with("7 x"))
        .unwrap()
        .to_string();
    // The same point twice.
    rejected(
        store,
        &path,
        &good
            .replace("points 1\n", "points 2\n")
            .replace(&format!("{point}\n"), &format!("{point}\n{point}\n")),
    );
    // The same record twice.
    let (line, _) = record_line(&good, 1);
    rejected(
        store,
        &path,
        &good
            .replace("records 2\n", "records 3\n")
            .replace(&format!("{line}\n"), &format!("{line}\n{line}\n")),
    );
    // The same increment twice.
    rejected(
        store,
        &path,
        &good.replace("increments 2 1 ", "increments 3 1 1 1 "),
    );
    // A schedule naming an increment the sweep never ran, or not ascending.
    for next in ["next 1 1 9", "next 1 2 2 1", "next 2 2 1 1"] {
        rejected(store, &path, &good.replacen("next 0 0", next, 1));
    }
    unsafe { jointlin_store_free(store) };
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn counters_near_u32_max_are_rejected_not_wrapped() {
    let dir = fresh_dir("counters");
    let path = dir.join("store.restart");
    let store = store_at(&path, 1e-3, b"model A");
    let good = real_file(store, &path);
    let (line, tokens) = record_line(&good, 2);
    // Record passes, estimate pass and reported pass beyond the passes run (u32::MAX
    // wrapped to 0 at the next LOP 2).
    for slot in [2usize, 6, 10] {
        for v in ["4294967295", "4294967294", "2"] {
            let mut t = tokens.clone();
            t[slot] = v.to_string();
            rejected(store, &path, &good.replace(&line, &t.join(" ")));
        }
    }
    // Iteration passes beyond the passes started; pass statistics that contradict
    // themselves.
    let stats = "\n1 0 2 0 2 0\n";
    assert!(
        good.contains(stats) && good.contains("counters 0 0"),
        "{good}"
    );
    rejected(
        store,
        &path,
        &good.replace("counters 0 0", "counters 4294967295 0"),
    );
    rejected(
        store,
        &path,
        &good.replace(stats, "\n1 0 2 4294967295 2 0\n"),
    );
    rejected(
        store,
        &path,
        &good.replace(stats, "\n1 0 2 0 2 4294967295\n"),
    );
    rejected(store, &path, &good.replace(stats, "\n7 0 2 0 2 0\n"));
    // The good file restores and the sweep goes on.
    std::fs::write(&path, &good).unwrap();
    assert_eq!(uexternaldb(store, 4, 0, 1, 0), JOINTLIN_OK);
    assert_eq!(uexternaldb(store, 3, 0, 1, 0), JOINTLIN_OK);
    unsafe { jointlin_store_free(store) };
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn lop_2_and_3_are_all_or_nothing_when_the_restart_file_cannot_be_written() {
    // LOP 2/3 returned JOINTLIN_ERR_IO after the store had advanced (the increment closed,
    // the pass decided), so the host's retry got JOINTLIN_ERR_SEQUENCE. Now a failed write
    // leaves the store where it was and the same call succeeds once the disk is back.
    let dir = fresh_dir("atomic");
    let sub = dir.join("sub");
    std::fs::create_dir_all(&sub).unwrap();
    let path = sub.join("store.restart");
    let store = store_at(&path, 1e-3, b"model A");
    let good = real_file(store, &path);
    assert_eq!(uexternaldb(store, 1, 0, 1, 3), 0);
    let mut amp = [0.0; 2];
    assert_eq!(
        unsafe { jointlin_store_estimate(store, 1, 3, amp.as_mut_ptr()) },
        0
    );
    assert_eq!(
        unsafe { jointlin_store_report(store, 1, 3, [1e-4, 1e-4].as_ptr()) },
        0
    );
    std::fs::remove_dir_all(&sub).unwrap();
    for _ in 0..2 {
        assert_eq!(uexternaldb(store, 2, 1, 1, 3), JOINTLIN_ERR_IO);
    }
    // Still open: the report can be repeated, and the estimate is the same.
    let mut again = [0.0; 2];
    assert_eq!(
        unsafe { jointlin_store_estimate(store, 1, 3, again.as_mut_ptr()) },
        0
    );
    assert_eq!(again, amp);
    std::fs::create_dir_all(&sub).unwrap();
    assert_eq!(uexternaldb(store, 2, 1, 1, 3), JOINTLIN_OK);
    let mut st = jointlin_point_status::default();
    assert_eq!(
        unsafe { jointlin_store_point_status(store, 1, 3, &mut st) },
        0
    );
    assert_eq!(st.passes, 1);
    // LOP 3: the pass stays running until its decision is written.
    std::fs::remove_dir_all(&sub).unwrap();
    assert_eq!(uexternaldb(store, 3, 0, 1, 0), JOINTLIN_ERR_IO);
    let (mut action, mut pass) = (0, 0);
    let status = unsafe { jointlin_store_next_action(store, &mut action, &mut pass) };
    assert_eq!(status, JOINTLIN_OK);
    assert_eq!(
        action, JOINTLIN_ACTION_RUNNING,
        "still running after a failed LOP 3"
    );
    std::fs::create_dir_all(&sub).unwrap();
    assert_eq!(uexternaldb(store, 3, 0, 1, 0), JOINTLIN_OK);
    assert_eq!(next_action(store), (JOINTLIN_ACTION_RUN_PASS, 2));
    assert_ne!(std::fs::read_to_string(&path).unwrap(), good);
    unsafe { jointlin_store_free(store) };
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every single-byte change of a restart file (each byte replaced by a neighbour
/// character), and every file cut short, is rejected by its checksum line; before the
/// checksum about half of such edits still parsed as a valid file.
#[test]
fn every_single_byte_edit_or_cut_is_rejected_by_the_checksum() {
    let dir = fresh_dir("checksum");
    let path = dir.join("jointlin.restart");
    let store = store_at(&path, 1e-6, b"deck v1");
    let good = real_file(store, &path);
    assert!(
        good.lines().last().unwrap().starts_with("checksum "),
        "{good}"
    );
    let before = status_of(store);
    let mut edits = 0;
    for i in 0..good.len() {
        let mut bytes = good.clone().into_bytes();
        bytes[i] = if bytes[i] == b'0' { b'1' } else { bytes[i] ^ 1 };
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(
            unsafe { jointlin_store_restore(store) },
            JOINTLIN_ERR_IO,
            "byte {i} changed: accepted"
        );
        edits += 1;
    }
    for n in (0..good.len()).step_by(3) {
        std::fs::write(&path, &good[..n]).unwrap();
        assert_eq!(
            unsafe { jointlin_store_restore(store) },
            JOINTLIN_ERR_IO,
            "cut at {n}"
        );
    }
    assert!(edits > 300, "{edits}");
    assert_eq!(status_of(store), before);
    std::fs::write(&path, &good).unwrap();
    assert_eq!(unsafe { jointlin_store_restore(store) }, JOINTLIN_OK);
    unsafe { jointlin_store_free(store) };
    let _ = std::fs::remove_dir_all(&dir);
}

/// UINTER of the steady-state step (LINPER = 1) at increment `kinc` for a point at node
/// `node` with `props`, closed by a static call before (h = 2e-4): the return code.
fn sweep_uinter(store: *const jointlin_store, node: i32, props: Vec<f64>, kinc: i32) -> i32 {
    let mut u = Uinter::new(props, 2);
    u.node = node;
    u.coords = [node as f64, 0.0, 0.0];
    assert_eq!(u.step_to([2e-4, 0.0, 0.0]), JOINTLIN_OK);
    u.linper = 1;
    u.freqr = 100.0;
    u.kinc = kinc;
    u.call(store)
}

#[test]
fn a_restart_file_of_another_mesh_or_law_is_refused_at_the_first_point_it_does_not_list() {
    // The Abaqus route: the shim restores jointlin.restart at LOP 0, before any UINTER
    // call tells it the deck's points. A file another job left (other nodes, or the same
    // mesh with other PROPS) lists other points: the first UINTER of a point it does not
    // list is JOINTLIN_ERR_IO naming that point, where it was a silent restart before.
    let dir = fresh_dir("another-model");
    let path = dir.join("jointlin.restart");
    let writer = store_at(&path, 1e-3, b"");
    assert_eq!(uexternaldb(writer, 0, 0, 1, 0), JOINTLIN_OK);
    assert_eq!(uexternaldb(writer, 1, 0, 1, 1), JOINTLIN_OK);
    for node in [1, 2] {
        assert_eq!(sweep_uinter(writer, node, block_props(), 1), JOINTLIN_OK);
    }
    assert_eq!(uexternaldb(writer, 2, 1, 1, 1), JOINTLIN_OK);
    let mut other_law = block_props();
    other_law[2] = 0.2; // μ
    for (node, props, expected) in [
        (1, block_props(), JOINTLIN_OK),
        (3, block_props(), JOINTLIN_ERR_IO),
        (2, other_law, JOINTLIN_ERR_IO),
    ] {
        let reader = store_at(&path, 1e-3, b"");
        assert_eq!(uexternaldb(reader, 4, 0, 1, 0), JOINTLIN_OK);
        assert_eq!(uexternaldb(reader, 1, 0, 1, 2), JOINTLIN_OK);
        assert_eq!(
            sweep_uinter(reader, node, props, 2),
            expected,
            "node {node}"
        );
        if expected != JOINTLIN_OK {
            let message = last_error();
            assert!(
                message.contains("restart file written for another model")
                    && message.contains(&format!("node {node}")),
                "{message}"
            );
        }
        unsafe { jointlin_store_free(reader) };
    }
    unsafe { jointlin_store_free(writer) };
    let _ = std::fs::remove_dir_all(&dir);
}
