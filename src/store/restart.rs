//! The restart file: a versioned, whitespace-separated token stream; floats as the hex of
//! their bits so that a round trip is exact.
//!
//! Version 2 carries the host's model fingerprint and the store's settings: a file
//! written for another model or with other settings is rejected at restore, as is every
//! file whose values a store could not have written (NaN, ∞ or negative amplitudes,
//! duplicate points, increments or records, counters beyond [`MAX_RESTART_PASSES`],
//! schedules naming increments the sweep never ran). Version 1 files (no fingerprints) are
//! read only by a store without a model fingerprint, with the same checks. Version 3 is
//! version 2 with a last line `checksum <crc32>` over every byte before it: a file
//! changed or cut after it was written is rejected before it is read. Version 4 is
//! version 3 with each point's PROPS checksum (`p<crc32>`, `-` for a point never called
//! through UINTER): a restored store refuses a point the file does not list, or one it
//! lists with other PROPS (a file written for another mesh or another law). Versions 2
//! and 3 are refused (a one-byte edit of the version would turn a newer file into one):
//! delete them to start the iteration over.

use super::*;

const MAGIC: &str = "jointlin-store";
const VERSION: &str = "4";
/// The format with the checksum, without the points' PROPS checksums.
const VERSION_3: &str = "3";
/// The format with fingerprints and without the checksum.
const VERSION_2: &str = "2";
/// The tag of the checksum line that ends a version 3 file.
const CHECKSUM: &str = "checksum ";
/// The format before the fingerprints.
const VERSION_1: &str = "1";

/// What a restart file must match: the host's model fingerprint (bytes, possibly empty)
/// and the store's settings.
pub(super) struct Fingerprint<'a> {
    pub model: &'a [u8],
    pub config: &'a StoreConfig,
}

/// The settings that change what a restored store does, as tokens (floats as bits).
fn settings_tokens(c: &StoreConfig) -> Vec<String> {
    vec![
        format!("{:016x}", c.initial_amplitude.to_bits()),
        format!("{:016x}", c.rtol.to_bits()),
        format!("{:016x}", c.atol.to_bits()),
        format!("{:?}", c.scheme),
        c.max_passes.to_string(),
        c.sweep_step.to_string(),
        format!("{:?}", c.numbering),
    ]
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Bytes from `x<hex>` (ASCII hex digits only, so any other character is an error, not a
/// panic on a character boundary).
fn unhex(token: &str, what: &str) -> Result<Vec<u8>, StoreError> {
    let digits = token.strip_prefix('x').ok_or_else(|| bad(what))?.as_bytes();
    if digits.len() % 2 != 0 || !digits.iter().all(u8::is_ascii_hexdigit) {
        return Err(bad(what));
    }
    digits
        .chunks(2)
        .map(|p| {
            std::str::from_utf8(p)
                .ok()
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| bad(what))
        })
        .collect()
}

fn f(out: &mut String, x: f64) {
    out.push_str(&format!(" {:016x}", x.to_bits()));
}

fn ints(out: &mut String, list: &[i32]) {
    out.push_str(&format!(" {}", list.len()));
    for k in list {
        out.push_str(&format!(" {k}"));
    }
}

pub(super) fn write(
    keys: &[PointKey],
    props: &[Option<u32>],
    s: &State,
    fp: &Fingerprint,
) -> String {
    let mut o = format!("{MAGIC} {VERSION}\n");
    o.push_str(&format!(
        "model x{}\nsettings {}\n",
        hex(fp.model),
        settings_tokens(fp.config).join(" ")
    ));
    let (code, list): (i32, &[i32]) = match &s.next {
        Action::RunSweep => (0, &[]),
        Action::RunPass(l) => (1, l),
        Action::RunFinal(l) => (2, l),
        Action::Done => (3, &[]),
        Action::Failed(l) => (4, l),
    };
    o.push_str(&format!("next {code}"));
    ints(&mut o, list);
    match &s.phase {
        Phase::Ready => o.push_str("\nphase 0"),
        Phase::Running(run) => {
            o.push_str(&format!("\nphase 1 {} {}", run.number, run.kind as i32));
            match &run.schedule {
                None => o.push_str(" 0"),
                Some(l) => {
                    o.push_str(" 1");
                    ints(&mut o, l);
                }
            }
            let ran: Vec<i32> = run.ran.iter().copied().collect();
            ints(&mut o, &ran);
        }
    }
    o.push_str(&format!("\ncounters {} {}\n", s.iteration_passes, s.step));
    o.push_str(&format!("stats {}\n", s.stats.len()));
    for st in &s.stats {
        o.push_str(&format!(
            "{} {} {} {} {} {}\n",
            st.number,
            st.kind as i32,
            st.increments_run,
            st.increments_converged,
            st.evaluations,
            st.not_reported
        ));
    }
    o.push_str(&format!("increments {}", s.increments.len()));
    for (k, ok) in &s.increments {
        o.push_str(&format!(" {k} {}", u8::from(*ok)));
    }
    o.push_str(&format!("\npoints {}\n", keys.len()));
    for (k, p) in keys.iter().zip(props) {
        o.push_str(&format!("{} x{} {}", k.node, hex(&k.name), k.coords.len()));
        for c in &k.coords {
            o.push_str(&format!(" {c:016x}"));
        }
        match p {
            Some(p) => o.push_str(&format!(" p{p:08x}\n")),
            None => o.push_str(" -\n"),
        }
    }
    let n: usize = s.records.iter().map(BTreeMap::len).sum();
    o.push_str(&format!("records {n}\n"));
    for (i, recs) in s.records.iter().enumerate() {
        for (k, r) in recs {
            o.push_str(&format!("{} {k} {} {}", i + 1, r.estimate_pass, r.dirs));
            f(&mut o, r.estimate[0]);
            f(&mut o, r.estimate[1]);
            o.push_str(&format!(" {}", r.reported_pass));
            f(&mut o, r.reported[0]);
            f(&mut o, r.reported[1]);
            o.push_str(&format!(
                " {} {} {}",
                u8::from(r.converged),
                r.passes,
                r.reason as i32
            ));
            for h in &r.history {
                o.push_str(&format!(" {}", h.len()));
                for &(a, b) in h {
                    f(&mut o, a);
                    f(&mut o, b);
                }
            }
            o.push('\n');
        }
    }
    o.push_str("end\n");
    let crc = crc32fast::hash(o.as_bytes());
    o.push_str(&format!("{CHECKSUM}{crc:08x}\n"));
    o
}

/// The text before the checksum line of a version 3 file, checked against it.
fn checked_body(text: &str) -> Result<&str, StoreError> {
    let mismatch = || {
        StoreError::Io(
            "restart file checksum mismatch: the file was changed or cut after it was written"
                .into(),
        )
    };
    let (body, sum) = text.rsplit_once(CHECKSUM).ok_or_else(mismatch)?;
    let sum = sum.strip_suffix('\n').ok_or_else(mismatch)?;
    let want = u32::from_str_radix(sum, 16).map_err(|_| mismatch())?;
    if sum.len() != 8 || crc32fast::hash(body.as_bytes()) != want {
        return Err(mismatch());
    }
    Ok(body)
}

struct Tokens<'a>(std::str::SplitWhitespace<'a>);

fn bad(what: &str) -> StoreError {
    StoreError::Io(format!("corrupt restart file: {what}"))
}

impl<'a> Tokens<'a> {
    fn word(&mut self, what: &str) -> Result<&'a str, StoreError> {
        self.0.next().ok_or_else(|| bad(what))
    }
    fn tag(&mut self, tag: &str) -> Result<(), StoreError> {
        if self.word(tag)? == tag {
            Ok(())
        } else {
            Err(bad(tag))
        }
    }
    fn int<T: std::str::FromStr>(&mut self, what: &str) -> Result<T, StoreError> {
        self.word(what)?.parse().map_err(|_| bad(what))
    }
    fn float(&mut self, what: &str) -> Result<f64, StoreError> {
        let x = u64::from_str_radix(self.word(what)?, 16).map_err(|_| bad(what))?;
        Ok(f64::from_bits(x))
    }
    /// An amplitude: finite and ≥ 0, as the store only ever holds.
    fn amplitude(&mut self, what: &str) -> Result<f64, StoreError> {
        let a = self.float(what)?;
        if a.is_finite() && a >= 0.0 {
            Ok(a)
        } else {
            Err(bad(&format!(
                "{what} {a:e} (amplitudes are finite and >= 0)"
            )))
        }
    }
    fn list(&mut self, what: &str) -> Result<Vec<i32>, StoreError> {
        let n: usize = self.int(what)?;
        (0..n).map(|_| self.int(what)).collect()
    }
}

pub(super) fn parse(text: &str, fp: &Fingerprint) -> Result<(Registry, State), StoreError> {
    let mut head = text.split_whitespace();
    let text = match (head.next(), head.next()) {
        (Some(MAGIC), Some(VERSION)) => checked_body(text)?,
        _ => text,
    };
    let mut t = Tokens(text.split_whitespace());
    t.tag(MAGIC)?;
    let version = t.word("version")?;
    match version {
        VERSION_2 => {
            return Err(StoreError::Io(
                "restart file of version 2 has no checksum (an earlier jointlin wrote it): delete it to start the iteration over".into(),
            ))
        }
        VERSION_3 => {
            return Err(StoreError::Io(
                "restart file of version 3 has no PROPS per point (an earlier jointlin wrote it): delete it to start the iteration over".into(),
            ))
        }
        VERSION => {
            t.tag("model")?;
            if unhex(t.word("model")?, "model fingerprint")? != fp.model {
                return Err(StoreError::Io(
                    "restart file written for another model (model fingerprint differs)".into(),
                ));
            }
            t.tag("settings")?;
            for (i, want) in settings_tokens(fp.config).iter().enumerate() {
                if t.word("settings")? != want {
                    return Err(StoreError::Io(format!(
                        "restart file written with other store settings (setting {} differs)",
                        i + 1
                    )));
                }
            }
        }
        VERSION_1 if fp.model.is_empty() => {}
        VERSION_1 => {
            return Err(StoreError::Io(
                "restart file of version 1 has no model fingerprint to check".into(),
            ))
        }
        _ => return Err(bad("unsupported version")),
    }
    t.tag("next")?;
    let code: i32 = t.int("next action")?;
    let list = t.list("next list")?;
    let next = match code {
        0 => Action::RunSweep,
        1 => Action::RunPass(list),
        2 => Action::RunFinal(list),
        3 => Action::Done,
        4 => Action::Failed(list),
        _ => return Err(bad("next action")),
    };
    t.tag("phase")?;
    let phase = match t.int::<i32>("phase")? {
        0 => Phase::Ready,
        1 => {
            let number = t.int("pass")?;
            let kind = kind(t.int("kind")?)?;
            let schedule = match t.int::<i32>("schedule")? {
                0 => None,
                _ => Some(t.list("schedule")?),
            };
            let ran = t.list("ran")?.into_iter().collect();
            Phase::Running(Run {
                number,
                kind,
                schedule,
                open: None,
                ran,
            })
        }
        _ => return Err(bad("phase")),
    };
    t.tag("counters")?;
    let iteration_passes = t.int("iteration passes")?;
    let step = t.int("step")?;
    t.tag("stats")?;
    let n: usize = t.int("stats")?;
    let mut stats = Vec::new();
    for _ in 0..n {
        stats.push(PassStats {
            number: t.int("stats")?,
            kind: kind(t.int("stats")?)?,
            increments_run: t.int("stats")?,
            increments_converged: t.int("stats")?,
            evaluations: t.int("stats")?,
            not_reported: t.int("stats")?,
        });
    }
    t.tag("increments")?;
    let n: usize = t.int("increments")?;
    let mut increments = BTreeMap::new();
    for _ in 0..n {
        let k = t.int("increment")?;
        let ok = match t.int::<u8>("increment flag")? {
            0 => false,
            1 => true,
            _ => return Err(bad("increment flag")),
        };
        if increments.insert(k, ok).is_some() {
            return Err(bad(&format!("increment {k} listed twice")));
        }
    }
    t.tag("points")?;
    let n: usize = t.int("points")?;
    let mut reg = Registry::default();
    for i in 0..n {
        let node = t.int("node")?;
        let name = unhex(t.word("name")?, "name")?;
        if name.len() > MAX_NAME_LEN {
            return Err(bad("name"));
        }
        let m: usize = t.int("coordinate count")?;
        if m > 3 {
            return Err(bad("coordinate count"));
        }
        let coords = (0..m)
            .map(|_| u64::from_str_radix(t.word("coordinate")?, 16).map_err(|_| bad("coordinate")))
            .collect::<Result<Vec<u64>, _>>()?;
        let props = match if version == VERSION {
            t.word("PROPS checksum")?
        } else {
            "-"
        } {
            "-" => None,
            w => Some(
                w.strip_prefix('p')
                    .filter(|h| h.len() == 8)
                    .and_then(|h| u32::from_str_radix(h, 16).ok())
                    .ok_or_else(|| bad("PROPS checksum"))?,
            ),
        };
        let key = PointKey { name, node, coords };
        if !reg.add(key, i as i64 + 1) {
            return Err(bad(&format!("point {} listed twice", i + 1)));
        }
        reg.props[i] = props;
    }
    t.tag("records")?;
    let n: usize = t.int("records")?;
    let mut records: Vec<BTreeMap<i32, Record>> = vec![BTreeMap::new(); reg.keys.len()];
    for _ in 0..n {
        let id: usize = t.int("record point")?;
        let k: i32 = t.int("record increment")?;
        let mut r = Record {
            estimate_pass: t.int("record")?,
            dirs: t.int("record")?,
            ..Record::default()
        };
        r.estimate = [t.amplitude("estimate")?, t.amplitude("estimate")?];
        r.reported_pass = t.int("record")?;
        r.reported = [t.amplitude("reported")?, t.amplitude("reported")?];
        r.converged = match t.int::<u8>("record")? {
            0 => false,
            1 => true,
            _ => return Err(bad("converged flag")),
        };
        r.passes = t.int("record")?;
        r.reason = match t.int::<i32>("reason")? {
            0 => Reason::None,
            1 => Reason::OutOfTolerance,
            2 => Reason::NotReported,
            _ => return Err(bad("reason")),
        };
        for d in 0..2 {
            let m: usize = t.int("history")?;
            for _ in 0..m {
                r.history[d].push((t.amplitude("history")?, t.amplitude("history")?));
            }
        }
        if id == 0 || id > records.len() || r.dirs > 2 {
            return Err(bad("record point"));
        }
        if records[id - 1].insert(k, r).is_some() {
            return Err(bad(&format!(
                "record of point {id} at increment {k} listed twice"
            )));
        }
    }
    t.tag("end")?;
    let state = State {
        phase,
        next,
        iteration_passes,
        step,
        increments,
        records,
        stats,
    };
    state
        .check_consistent(reg.keys.len())
        .map_err(|what| bad(&what))?;
    Ok((reg, state))
}

fn kind(code: i32) -> Result<PassKind, StoreError> {
    match code {
        0 => Ok(PassKind::First),
        1 => Ok(PassKind::Rerun),
        2 => Ok(PassKind::Final),
        _ => Err(bad("pass kind")),
    }
}

/// The restart file of rank `rank` of a job with several ranks: `<base>.r<rank>`.
pub(super) fn rank_path(base: &std::path::Path, rank: u32) -> PathBuf {
    let mut name = base.as_os_str().to_owned();
    name.push(format!(".r{rank}"));
    PathBuf::from(name)
}

/// `base` of a rank's restart file `<base>.r<rank>` ([`rank_path`]), if it is one.
pub(super) fn rank_base(path: &std::path::Path, rank: u32) -> Option<PathBuf> {
    let suffix = format!(".r{rank}");
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        let base = path
            .as_os_str()
            .as_bytes()
            .strip_suffix(suffix.as_bytes())?;
        Some(PathBuf::from(std::ffi::OsStr::from_bytes(base)))
    }
    #[cfg(not(unix))]
    {
        Some(PathBuf::from(path.to_str()?.strip_suffix(&suffix)?))
    }
}
