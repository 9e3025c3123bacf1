//! Several processes, one store each: the ranks of a domain-decomposed FE job (model.md §7).
//!
//! In a parallel Abaqus job every process (MPI rank) calls UEXTERNALDB, and UINTER for the
//! contact points of its own domain. Each rank keeps its own store for its own points and
//! its own restart file, `NAME.rRANK` ([`Store::new_ranked`]). An FE job re-runs whole
//! increments, so all ranks must decide alike which increments to re-run and whether the
//! iteration converged. Between the last LOP 2 of a pass and its LOP 3 each rank exports
//! its decision per sweep increment ([`Store::pass_summary`]: re-run, or converged on this
//! rank), the ranks take the element-wise maximum of the encoded summaries
//! ([`PassSummary::encode`]: an increment is re-run when any rank needs it), and each rank
//! imports the result ([`Store::pass_agree`]); LOP 3 then decides the next action from the
//! agreed flags, the same on every rank. The reduction is the host's (`MPI_Allreduce` with
//! `MPI_MAX` over its communicator: the library itself has no MPI dependency), or the file
//! protocol of [`Store::agree_by_files`] where no communicator is available.
//!
//! Why this equals the serial run bit for bit: a point's estimate depends only on its own
//! history and on the amplitude reported for the same point at the previous increment (never
//! on other points or on point ids), and the serial decision "increment k converged" is the
//! AND over all points queried at k, which is the AND over the ranks of each rank's AND.
//! Increments a pass did not run keep the flags all ranks agreed on before.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::*;

/// One rank's decision per sweep increment at the end of a pass (or the agreed decision
/// of all ranks).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PassSummary {
    /// The running pass (1-based).
    pub pass: u32,
    /// Every sweep increment the store knows, ascending.
    pub increments: Vec<i32>,
    /// Per increment: re-run it (not converged on this rank, or scheduled in this pass
    /// but not run).
    pub rerun: Vec<bool>,
}

/// Ranks that were not at the same point of the iteration.
fn disagree(msg: impl Into<String>) -> StoreError {
    StoreError::Sequence(msg.into())
}

impl PassSummary {
    /// Length of an encoded summary of `n` increments: 4 + 3n.
    pub fn encoded_len(n: usize) -> usize {
        4 + 3 * n
    }

    /// The summary as integers whose element-wise maximum over the ranks is the agreed
    /// summary: `[pass, −pass, n, −n, k_1 … k_n, −k_1 … −k_n, r_1 … r_n]` with r = 1 for
    /// re-run. The negated copies carry the minimum through the maximum (min x = −max −x),
    /// so a reduced summary shows whether all ranks were at the same pass with the same
    /// increments. Increment numbers must not be `i32::MIN` (its negation overflows).
    pub fn encode(&self) -> Result<Vec<i32>, StoreError> {
        let n = self.increments.len();
        if self.rerun.len() != n {
            return Err(StoreError::OutOfRange("one re-run flag per increment"));
        }
        if self.increments.contains(&i32::MIN) {
            return Err(StoreError::OutOfRange("increment number i32::MIN"));
        }
        let pass = i32::try_from(self.pass).map_err(|_| StoreError::OutOfRange("pass"))?;
        let count = i32::try_from(n).map_err(|_| StoreError::OutOfRange("increments"))?;
        let mut out = Vec::with_capacity(Self::encoded_len(n));
        out.extend([pass, -pass, count, -count]);
        out.extend(&self.increments);
        out.extend(self.increments.iter().map(|k| -k));
        out.extend(self.rerun.iter().map(|&r| i32::from(r)));
        Ok(out)
    }

    /// Decodes an encoded summary, in particular a reduced one. Errors: a malformed buffer
    /// (`OutOfRange`), or ranks that were not at the same pass with the same increments
    /// (`Sequence`).
    pub fn decode(buf: &[i32]) -> Result<Self, StoreError> {
        let bad = || StoreError::OutOfRange("malformed pass summary");
        if buf.len() < 4 || !(buf.len() - 4).is_multiple_of(3) {
            return Err(bad());
        }
        let n = (buf.len() - 4) / 3;
        let [pass, neg_pass, count, neg_count] = [buf[0], buf[1], buf[2], buf[3]];
        if pass != neg_pass.saturating_neg() {
            return Err(disagree(format!(
                "the ranks are at different passes ({} to {pass})",
                neg_pass.saturating_neg()
            )));
        }
        if count != neg_count.saturating_neg() {
            return Err(disagree(format!(
                "the ranks know different numbers of increments ({} to {count})",
                neg_count.saturating_neg()
            )));
        }
        if usize::try_from(count).ok() != Some(n) {
            return Err(bad());
        }
        let pass = u32::try_from(pass)
            .ok()
            .filter(|&p| p >= 1)
            .ok_or_else(bad)?;
        let (ks, rest) = buf[4..].split_at(n);
        let (neg, flags) = rest.split_at(n);
        if let Some(i) = (0..n).find(|&i| ks[i] != neg[i].saturating_neg()) {
            return Err(disagree(format!(
                "the ranks disagree on the {}th increment ({} to {})",
                i + 1,
                neg[i].saturating_neg(),
                ks[i]
            )));
        }
        if ks.windows(2).any(|w| w[0] >= w[1]) || flags.iter().any(|f| !(0..=1).contains(f)) {
            return Err(bad());
        }
        Ok(Self {
            pass,
            increments: ks.to_vec(),
            rerun: flags.iter().map(|&f| f == 1).collect(),
        })
    }

    /// `acc[i] = max(acc[i], other[i])`: what `MPI_Allreduce` with `MPI_MAX` computes, for
    /// hosts that reduce summaries themselves.
    pub fn reduce_max(acc: &mut [i32], other: &[i32]) -> Result<(), StoreError> {
        if acc.len() != other.len() {
            return Err(disagree(format!(
                "pass summaries of different lengths ({} and {}): the ranks know different \
                 numbers of increments",
                acc.len(),
                other.len()
            )));
        }
        for (a, &b) in acc.iter_mut().zip(other) {
            *a = (*a).max(b);
        }
        Ok(())
    }
}

/// This rank's summary of the running pass, from the store's state.
fn summary_of(state: &State) -> Result<PassSummary, StoreError> {
    let Phase::Running(run) = &state.phase else {
        return Err(seq(
            "no pass is running (the summary is taken between the last LOP 2 and LOP 3)",
        ));
    };
    if let Some((open, _, _)) = &run.open {
        return Err(seq(format!(
            "increment {open} is still open (LOP 2 missing)"
        )));
    }
    let unrun = |k: &i32| {
        run.schedule
            .as_ref()
            .is_some_and(|s| s.contains(k) && !run.ran.contains(k))
    };
    Ok(PassSummary {
        pass: run.number,
        increments: state.increments.keys().copied().collect(),
        rerun: state
            .increments
            .iter()
            .map(|(k, &ok)| !ok || unrun(k))
            .collect(),
    })
}

/// How long [`Store::agree_by_files`] sleeps between looks for the other ranks' files.
const POLL: Duration = Duration::from_millis(20);

/// The file of rank `rank`'s summary of pass `pass`, beside its restart file
/// `<base>.r<rank>`: `<base>.r<rank>.pass<pass>`.
fn pass_file(base: &Path, rank: u32, pass: u32) -> PathBuf {
    let mut name = restart::rank_path(base, rank).into_os_string();
    name.push(format!(".pass{pass}"));
    PathBuf::from(name)
}

/// First line of a pass file; then the encoded summary, integers separated by blanks.
const PASS_MAGIC: &str = "jointlin-pass-summary 1";

fn read_pass_file(path: &Path) -> Result<Option<Vec<i32>>, StoreError> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(StoreError::Io(format!("reading {}: {e}", path.display()))),
    };
    let corrupt = || StoreError::Io(format!("{} is not a pass summary", path.display()));
    let body = text.strip_prefix(PASS_MAGIC).ok_or_else(corrupt)?;
    let ints = body
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<Vec<i32>, _>>()
        .map_err(|_| corrupt())?;
    PassSummary::decode(&ints).map_err(|_| corrupt())?;
    Ok(Some(ints))
}

impl Store {
    /// A store for rank `rank` (0-based) of `ranks` processes. With more than one rank the
    /// restart file, if configured, is `<restart_path>.r<rank>`; a rank whose restart file
    /// does not exist yet starts a new iteration and deletes its pass files of an earlier
    /// one (`<restart_path>.r<rank>.pass<P>`, see [`Store::agree_by_files`]). One rank is
    /// the plain store.
    pub fn new_ranked(config: StoreConfig, rank: u32, ranks: u32) -> Result<Self, StoreError> {
        if ranks == 0 || rank >= ranks {
            return Err(StoreError::OutOfRange("need 0 <= rank < ranks"));
        }
        let mut config = config;
        if ranks > 1 {
            config.restart_path = config
                .restart_path
                .map(|base| restart::rank_path(&base, rank));
        }
        let store = Self::new(config)?;
        if let (true, Some(path)) = (ranks > 1, &store.config.restart_path) {
            if !path.exists() {
                remove_pass_files(path)?;
            }
        }
        Ok(store)
    }

    /// This rank's decision per sweep increment for the running pass, between the last
    /// LOP 2 of the pass and its LOP 3.
    pub fn pass_summary(&self) -> Result<PassSummary, StoreError> {
        summary_of(&*self.state()?)
    }

    /// Takes the ranks' agreed decision (the reduction of all ranks' [`Store::pass_summary`])
    /// in place of this rank's own, between the last LOP 2 and LOP 3; LOP 3 then decides
    /// from it. The agreed summary must be of this pass and this store's increments, and
    /// re-run every increment this rank must re-run (a maximum that included this rank).
    pub fn pass_agree(&self, agreed: &PassSummary) -> Result<(), StoreError> {
        let mut state = self.state()?;
        let own = summary_of(&state)?;
        if agreed.pass != own.pass {
            return Err(seq(format!(
                "agreed summary of pass {}, but pass {} is running",
                agreed.pass, own.pass
            )));
        }
        if agreed.increments != own.increments || agreed.rerun.len() != own.rerun.len() {
            return Err(seq(format!(
                "agreed summary of increments {:?}, but this rank knows {:?}",
                agreed.increments, own.increments
            )));
        }
        if let Some(i) = (0..own.rerun.len()).find(|&i| own.rerun[i] && !agreed.rerun[i]) {
            return Err(seq(format!(
                "the agreed summary drops increment {}, which this rank must re-run (not a \
                 maximum over all ranks)",
                own.increments[i]
            )));
        }
        for (&k, &rerun) in agreed.increments.iter().zip(&agreed.rerun) {
            state.increments.insert(k, !rerun);
        }
        Ok(())
    }

    /// The file protocol for ranks without a shared communicator (the directory of the
    /// restart file must be shared by all ranks, as a job directory on a cluster file
    /// system is). Rank `rank` of `ranks`, between the last LOP 2 of pass P and its LOP 3:
    ///
    /// 1. writes its encoded summary to `<restart>.r<rank>.pass<P>` (a temporary file,
    ///    then a rename: a reader sees a whole file or none);
    /// 2. waits, polling every 20 ms for at most `timeout`, until the files of every rank
    ///    `<restart>.r<j>.pass<P>` exist;
    /// 3. reduces them by maximum and agrees ([`Store::pass_agree`]);
    /// 4. deletes its own file of pass P − 1: every rank has read those, since each rank
    ///    wrote its file of pass P only after agreeing on pass P − 1.
    ///
    /// The files of the last pass stay; a new iteration (no restart file) deletes them
    /// ([`Store::new_ranked`]). One rank agrees with itself and writes nothing. Errors:
    /// no restart path, a store not made by [`Store::new_ranked`] for this rank, a
    /// timeout (naming the ranks missing), unreadable files (`Io`); ranks at different
    /// passes or increments (`Sequence`).
    pub fn agree_by_files(
        &self,
        rank: u32,
        ranks: u32,
        timeout: Duration,
    ) -> Result<(), StoreError> {
        if ranks == 0 || rank >= ranks {
            return Err(StoreError::OutOfRange("need 0 <= rank < ranks"));
        }
        let summary = self.pass_summary()?;
        if ranks == 1 {
            return self.pass_agree(&summary);
        }
        let own = self.config.restart_path.as_ref().ok_or_else(|| {
            StoreError::Io("the file protocol needs a restart file: its files go beside it".into())
        })?;
        let base = restart::rank_base(own, rank).ok_or(StoreError::OutOfRange(
            "the store was not made for this rank (new_ranked)",
        ))?;
        let mine = summary.encode()?;
        let path = pass_file(&base, rank, summary.pass);
        let text = format!(
            "{PASS_MAGIC}\n{}\n",
            mine.iter()
                .map(i32::to_string)
                .collect::<Vec<_>>()
                .join(" ")
        );
        write_atomically(&path, &text)?;
        let mut reduced = mine;
        let mut missing: Vec<u32> = (0..ranks).filter(|&j| j != rank).collect();
        let deadline = Instant::now() + timeout;
        loop {
            let mut still = Vec::new();
            for &j in &missing {
                match read_pass_file(&pass_file(&base, j, summary.pass))? {
                    Some(theirs) => PassSummary::reduce_max(&mut reduced, &theirs)?,
                    None => still.push(j),
                }
            }
            missing = still;
            if missing.is_empty() {
                break;
            }
            if Instant::now() >= deadline {
                return Err(StoreError::Io(format!(
                    "no pass {} summary of rank(s) {missing:?} after {:.1} s (files {}, ...)",
                    summary.pass,
                    timeout.as_secs_f64(),
                    pass_file(&base, missing[0], summary.pass).display()
                )));
            }
            std::thread::sleep(POLL);
        }
        self.pass_agree(&PassSummary::decode(&reduced)?)?;
        if summary.pass > 1 {
            let old = pass_file(&base, rank, summary.pass - 1);
            match std::fs::remove_file(&old) {
                Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                    return Err(StoreError::Io(format!("removing {}: {e}", old.display())))
                }
                _ => {}
            }
        }
        Ok(())
    }
}

/// Writes `text` to `path` through a temporary file in the same directory and a rename.
fn write_atomically(path: &Path, text: &str) -> Result<(), StoreError> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(format!(".tmp{}", std::process::id()));
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, text)
        .and_then(|()| std::fs::rename(&tmp, path))
        .map_err(|e| StoreError::Io(format!("writing {}: {e}", path.display())))
}

/// Deletes `<restart>.pass<P>` files beside this rank's restart file `restart`.
fn remove_pass_files(restart: &Path) -> Result<(), StoreError> {
    let (Some(dir), Some(name)) = (restart.parent(), restart.file_name()) else {
        return Ok(());
    };
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let prefix = format!("{}.pass", name.to_string_lossy());
    let entries = match std::fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(StoreError::Io(format!("listing {}: {e}", dir.display()))),
    };
    for entry in entries.flatten() {
        let file = entry.file_name();
        let file = file.to_string_lossy();
        let is_pass = file
            .strip_prefix(&prefix)
            .is_some_and(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()));
        if is_pass {
            std::fs::remove_file(entry.path())
                .map_err(|e| StoreError::Io(format!("removing {}: {e}", file)))?;
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "ranks_tests.rs"]
mod tests;
