//! The UEXTERNALDB-side iteration store (thesis §4.3.2, Fig. 4.27; model.md §6–7).
//!
//! k*, d* of a contact point depend on the vibration amplitude they are linearized for, and
//! that amplitude is the result of the steady-state analysis. The thesis iterates over whole
//! frequency sweeps: pass 1 runs every frequency increment (KINC), the first with a
//! user-given amplitude estimate and each later one with the amplitude computed at the
//! previous increment; after the pass, estimate and computed amplitude are compared per
//! point and increment; the increments out of tolerance are re-run in a new pass; when none
//! is left, one final pass over all increments writes the results.
//!
//! This store holds, per contact point × increment and for both tangential directions, the
//! estimate handed out, the amplitude the host reported back, the (estimate, computed)
//! history of earlier passes (fed to the shared rule [`crate::iterate::next_estimate`]), the converged flag
//! and the pass count. It follows Abaqus's UEXTERNALDB calls ([`Store::external_db`]: LOP
//! 0 start of analysis, 1 start of increment, 2 end of increment, 3 end of analysis, 4
//! start of a restart analysis, 5 start of step, 6 end of step) and says what to run next
//! ([`Action`]).
//!
//! Many host threads may query estimates and report amplitudes at once: the point registry
//! sits behind an `RwLock`, the iteration state behind a `Mutex`, each held only for a few
//! map operations (never during file I/O).

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard, RwLock};

/// Errors of the iteration store. Each maps to one C status code in `ffi/error.rs`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum StoreError {
    /// An input was NaN or ±∞.
    #[error("non-finite input: {0}")]
    NonFinite(&'static str),
    /// An input was finite but outside its valid range.
    #[error("input out of range: {0}")]
    OutOfRange(&'static str),
    /// A point id that was never registered.
    #[error("unknown contact point id {0}")]
    UnknownPoint(i64),
    /// A host node with several registered points (one per interaction): a report by
    /// node cannot tell which point it means.
    #[error("node {node}: {points} contact points (a report by node needs one)")]
    Node { node: i32, points: usize },
    /// A call that does not fit the LOP sequence (e.g. an estimate outside an increment).
    #[error("call out of sequence: {0}")]
    Sequence(String),
    /// Reading or writing the restart file failed, or its content is not a store.
    #[error("restart file: {0}")]
    Io(String),
    /// A panic while the store was locked left it in an unknown state.
    #[error("the store was poisoned by an earlier panic")]
    Poisoned,
}

/// What the host should do next.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Action {
    /// Run pass 1: the whole sweep.
    RunSweep,
    /// Re-run these sweep increments (ascending).
    RunPass(Vec<i32>),
    /// All increments converged: run the final pass over all of them (ascending).
    RunFinal(Vec<i32>),
    /// The final pass confirmed every increment: finished.
    Done,
    /// Increments are still out of tolerance after `max_passes` iteration passes.
    Failed(Vec<i32>),
}

/// Kind of a pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PassKind {
    First = 0,
    Rerun = 1,
    Final = 2,
}

/// Counts of one pass (what Fig. 4.33 plots: frequencies per analysis).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PassStats {
    pub number: u32,
    pub kind: PassKind,
    /// Increments run in this pass.
    pub increments_run: u32,
    /// Of those, the ones where every queried point converged.
    pub increments_converged: u32,
    /// Point × increment evaluations compared at LOP 2.
    pub evaluations: u64,
    /// Of those, points queried but never reported back.
    pub not_reported: u64,
}

/// Why a point × increment is not converged.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Reason {
    /// Converged (or never evaluated).
    #[default]
    None = 0,
    /// |a − a*| above the tolerance in some direction.
    OutOfTolerance = 1,
    /// The point was queried in the increment but no amplitude was reported.
    NotReported = 2,
}

/// What the store knows about one point in one sweep increment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointStatus {
    /// Estimate handed out in the latest pass that queried the point here.
    pub estimate: [f64; 2],
    /// Latest amplitude reported back (0 when none yet).
    pub computed: [f64; 2],
    /// Number of tangential directions compared (1 or 2).
    pub directions: usize,
    pub converged: bool,
    /// Passes in which this point was evaluated at this increment.
    pub passes: u32,
    pub reason: Reason,
}

#[derive(Debug, Clone, Default, PartialEq)]
struct Record {
    estimate: [f64; 2],
    /// Pass in which `estimate` was handed out (0: never).
    estimate_pass: u32,
    /// Directions used by the querying host (1 or 2).
    dirs: usize,
    reported: [f64; 2],
    /// Pass in which `reported` arrived (0: never).
    reported_pass: u32,
    history: [Vec<(f64, f64)>; 2],
    converged: bool,
    passes: u32,
    reason: Reason,
}

#[derive(Debug, Clone, PartialEq)]
enum Phase {
    Ready,
    Running(Run),
}

#[derive(Debug, Clone, PartialEq)]
struct Run {
    number: u32,
    kind: PassKind,
    /// Scheduled sweep increments (None in pass 1: whatever the sweep runs).
    schedule: Option<Vec<i32>>,
    /// Open increment: (host KINC, sweep KINC, points queried).
    open: Option<(i32, i32, BTreeSet<i64>)>,
    /// Sweep increments closed (LOP 2) in this pass.
    ran: BTreeSet<i32>,
}

#[derive(Debug, Clone, PartialEq)]
struct State {
    phase: Phase,
    next: Action,
    /// Iteration passes done (pass 1, re-runs, final passes that failed).
    iteration_passes: u32,
    /// Current step from LOP 5 (0 before any).
    step: i32,
    /// All sweep increments and whether they are converged.
    increments: BTreeMap<i32, bool>,
    /// Records per point (index id − 1) and sweep increment.
    records: Vec<BTreeMap<i32, Record>>,
    stats: Vec<PassStats>,
}

/// Longest model fingerprint accepted (bytes).
pub const MAX_MODEL_LEN: usize = 4096;

/// Passes beyond this in a restart file mean the file is not a store's (a real sweep stops
/// at `max_passes`, a u32 from the host's configuration, long before).
const MAX_RESTART_PASSES: u32 = 1 << 20;

impl State {
    /// Invariants the store relies on, checked on a restored state so that a file that parses
    /// but contradicts itself is an error at LOP 4, not a panic later.
    fn check_consistent(&self, points: usize) -> Result<(), String> {
        if self.records.len() != points {
            return Err(format!(
                "{} record lists for {points} points",
                self.records.len()
            ));
        }
        let passes = self.stats.len();
        if passes > MAX_RESTART_PASSES as usize || self.iteration_passes as usize > passes {
            return Err(format!(
                "{} iteration passes of {passes} passes",
                self.iteration_passes
            ));
        }
        for (i, st) in self.stats.iter().enumerate() {
            if st.number as usize != i + 1
                || st.increments_converged > st.increments_run
                || st.not_reported > st.evaluations
            {
                return Err(format!(
                    "statistics of pass {} contradict themselves",
                    i + 1
                ));
            }
        }
        // Every increment named anywhere is one the sweep ran, each list ascending without
        // repeats (a file from another model scheduled increments that do not exist).
        let known = |list: &[i32], what: &str| -> Result<(), String> {
            let ascending = list.windows(2).all(|w| w[0] < w[1]);
            match list.iter().find(|k| !self.increments.contains_key(k)) {
                Some(k) => Err(format!("{what} names increment {k}, never run")),
                None if !ascending => Err(format!("{what} is not ascending")),
                None => Ok(()),
            }
        };
        match &self.next {
            Action::RunPass(l) | Action::RunFinal(l) | Action::Failed(l) => known(l, "next")?,
            Action::RunSweep | Action::Done => {}
        }
        for (id, recs) in self.records.iter().enumerate() {
            for (k, r) in recs {
                known(&[*k], "a record")?;
                let pass_ok = |p: u32| p as usize <= passes;
                if !pass_ok(r.estimate_pass) || !pass_ok(r.reported_pass) || !pass_ok(r.passes) {
                    return Err(format!(
                        "record of point {} at {k} names a pass beyond {passes}",
                        id + 1
                    ));
                }
            }
        }
        if let Phase::Running(run) = &self.phase {
            if self.stats.last().map(|s| (s.number, s.kind)) != Some((run.number, run.kind)) {
                return Err(format!("running pass {} has no statistics", run.number));
            }
            if let Some(list) = &run.schedule {
                known(list, "the running pass's schedule")?;
            }
            let ran: Vec<i32> = run.ran.iter().copied().collect();
            known(&ran, "the running pass")?;
            if let Some((_, sweep, touched)) = &run.open {
                for &id in touched {
                    let ok = id >= 1
                        && (id as usize) <= points
                        && self.records[id as usize - 1].contains_key(sweep);
                    if !ok {
                        return Err(format!(
                            "open increment {sweep} names point {id} without a record"
                        ));
                    }
                }
            }
        }
        Ok(())
    }

    fn new() -> Self {
        Self {
            phase: Phase::Ready,
            next: Action::RunSweep,
            iteration_passes: 0,
            step: 0,
            increments: BTreeMap::new(),
            records: Vec::new(),
            stats: Vec::new(),
        }
    }
}

#[derive(Debug, Default)]
struct Registry {
    ids: HashMap<PointKey, i64>,
    keys: Vec<PointKey>,
    /// Point ids per host node (several where interactions share a node).
    by_node: HashMap<i32, Vec<i64>>,
    /// Per point: the CRC-32 of the PROPS it was last called with through UINTER
    /// ([`props_checksum`]), None before.
    props: Vec<Option<u32>>,
    /// Restored from a restart file that listed points: the model's points are those,
    /// and a new one, or one with other PROPS, means the file was written for another
    /// model.
    restored: bool,
}

impl Registry {
    /// Adds `key` as point `id` (the next one); false if the key is already registered.
    fn add(&mut self, key: PointKey, id: i64) -> bool {
        if self.ids.contains_key(&key) {
            return false;
        }
        self.by_node.entry(key.node).or_default().push(id);
        self.keys.push(key.clone());
        self.props.push(None);
        self.ids.insert(key, id);
        true
    }
}

/// The iteration store. `Sync`: share it between host threads by reference.
#[derive(Debug)]
pub struct Store {
    config: StoreConfig,
    /// The host's model fingerprint (bytes), written to and checked in the restart file.
    model: RwLock<Vec<u8>>,
    registry: RwLock<Registry>,
    state: Mutex<State>,
}

fn seq(msg: impl Into<String>) -> StoreError {
    StoreError::Sequence(msg.into())
}

impl Store {
    pub fn new(config: StoreConfig) -> Result<Self, StoreError> {
        config.validate()?;
        Ok(Self {
            config,
            model: RwLock::new(Vec::new()),
            registry: RwLock::new(Registry::default()),
            state: Mutex::new(State::new()),
        })
    }

    pub fn config(&self) -> &StoreConfig {
        &self.config
    }

    /// Sets the host's model fingerprint: bytes that identify the model the sweep runs
    /// (at most [`MAX_MODEL_LEN`]), e.g. a hash of the input deck. The restart file
    /// carries it, and [`Store::restore`] rejects a file with another one.
    pub fn set_model(&self, fingerprint: &[u8]) -> Result<(), StoreError> {
        if fingerprint.len() > MAX_MODEL_LEN {
            return Err(StoreError::OutOfRange(
                "model fingerprint longer than 4096 bytes",
            ));
        }
        *self.model.write().map_err(|_| StoreError::Poisoned)? = fingerprint.to_vec();
        Ok(())
    }

    fn model(&self) -> Result<Vec<u8>, StoreError> {
        Ok(self.model.read().map_err(|_| StoreError::Poisoned)?.clone())
    }

    fn state(&self) -> Result<MutexGuard<'_, State>, StoreError> {
        self.state.lock().map_err(|_| StoreError::Poisoned)
    }

    /// Stable 1-based id of the point with this key; the same key always gives the same id.
    /// After a restore from a file that listed points, a key not among them is
    /// [`StoreError::Io`]: the file was written for another model.
    pub fn register(&self, key: PointKey) -> Result<i64, StoreError> {
        if let Some(&id) = self
            .registry
            .read()
            .map_err(|_| StoreError::Poisoned)?
            .ids
            .get(&key)
        {
            return Ok(id);
        }
        let mut reg = self.registry.write().map_err(|_| StoreError::Poisoned)?;
        if let Some(&id) = reg.ids.get(&key) {
            return Ok(id); // registered by another thread in between
        }
        if reg.restored {
            return Err(StoreError::Io(format!(
                "restart file written for another model: point {key} is not among its {} points (another mesh or interaction); delete the file to start the iteration over",
                reg.keys.len()
            )));
        }
        let id = reg.keys.len() as i64 + 1;
        reg.add(key, id);
        Ok(id)
    }

    /// Notes that point `id` was called with PROPS of checksum `checksum`
    /// ([`props_checksum`]). After a restore, a point the file lists with other PROPS is
    /// [`StoreError::Io`]: the file was written for another model.
    pub fn check_props(&self, id: i64, checksum: u32) -> Result<(), StoreError> {
        self.check_point(id)?;
        let slot = id as usize - 1;
        let reg = self.registry.read().map_err(|_| StoreError::Poisoned)?;
        if reg.props[slot] == Some(checksum) {
            return Ok(());
        }
        drop(reg);
        let mut reg = self.registry.write().map_err(|_| StoreError::Poisoned)?;
        match reg.props[slot] {
            Some(old) if reg.restored && old != checksum => Err(StoreError::Io(format!(
                "restart file written for another model: point {} had PROPS of checksum {old:08x}, this call's are {checksum:08x}; delete the file to start the iteration over",
                reg.keys[slot]
            ))),
            _ => {
                reg.props[slot] = Some(checksum);
                Ok(())
            }
        }
    }

    /// The id of the point registered for host node `node` (the NODE of its UINTER
    /// call), for hosts that know their results per node (an Abaqus URDFIL reading
    /// contact output); None if no point has that node (e.g. a slave node never in
    /// contact), [`StoreError::Node`] if several have.
    pub fn point_of_node(&self, node: i32) -> Result<Option<i64>, StoreError> {
        let reg = self.registry.read().map_err(|_| StoreError::Poisoned)?;
        match reg.by_node.get(&node).map(Vec::as_slice) {
            None | Some(&[]) => Ok(None),
            Some(&[id]) => Ok(Some(id)),
            Some(ids) => Err(StoreError::Node {
                node,
                points: ids.len(),
            }),
        }
    }

    /// `hint` when it is the id of `key` (e.g. the id a host kept in STATEV), else the key's
    /// id, registering it if new.
    pub fn resolve(&self, hint: i64, key: PointKey) -> Result<i64, StoreError> {
        if hint >= 1 {
            let reg = self.registry.read().map_err(|_| StoreError::Poisoned)?;
            if reg.keys.get(hint as usize - 1) == Some(&key) {
                return Ok(hint);
            }
        }
        self.register(key)
    }

    /// Number of registered points.
    pub fn point_count(&self) -> Result<i64, StoreError> {
        Ok(self
            .registry
            .read()
            .map_err(|_| StoreError::Poisoned)?
            .keys
            .len() as i64)
    }

    fn check_point(&self, id: i64) -> Result<(), StoreError> {
        if id >= 1 && id <= self.point_count()? {
            Ok(())
        } else {
            Err(StoreError::UnknownPoint(id))
        }
    }

    /// Sweep increment of the open increment for a host KINC, with the pass number.
    fn current(state: &State, kinc: i32) -> Result<(u32, i32), StoreError> {
        let Phase::Running(run) = &state.phase else {
            return Err(seq("no pass is running (LOP 0 missing)"));
        };
        match &run.open {
            Some((host, sweep, _)) if *host == kinc => Ok((run.number, *sweep)),
            Some((host, _, _)) => Err(seq(format!(
                "KINC {kinc} is not the open increment {host} (LOP 1)"
            ))),
            None => Err(seq("no increment is open (LOP 1 missing)")),
        }
    }

    /// Amplitude estimates (length) of point `id` in the open increment `kinc` for both
    /// tangential directions; `directions` (1 or 2) of them take part in the convergence
    /// test. The estimate is fixed at the first query of a pass; later queries return it.
    pub fn estimate(&self, id: i64, kinc: i32, directions: usize) -> Result<[f64; 2], StoreError> {
        if !(1..=2).contains(&directions) {
            return Err(StoreError::OutOfRange(
                "tangential directions must be 1 or 2",
            ));
        }
        self.check_point(id)?;
        let mut guard = self.state()?;
        let state = &mut *guard;
        let (pass, sweep) = Self::current(state, kinc)?;
        let idx = id as usize - 1;
        if state.records.len() <= idx {
            state.records.resize_with(idx + 1, BTreeMap::new);
        }
        let records = &mut state.records[idx];
        // Thesis rule: the amplitude computed at the nearest earlier increment.
        let previous = records
            .range(..sweep)
            .rev()
            .find(|(_, r)| r.reported_pass > 0)
            .map(|(_, r)| r.reported);
        let rec = records.entry(sweep).or_default();
        if rec.estimate_pass != pass {
            let fallback = previous.unwrap_or([self.config.initial_amplitude; 2]);
            for (d, &back) in fallback.iter().enumerate() {
                rec.estimate[d] = if rec.history[d].is_empty() {
                    back
                } else {
                    let hist = &rec.history[d];
                    self.config
                        .next_from(&hist[hist.len().saturating_sub(HISTORY_WINDOW)..])
                };
            }
            rec.estimate_pass = pass;
            rec.dirs = 0;
        }
        rec.dirs = rec.dirs.max(directions);
        let estimate = rec.estimate;
        if let Phase::Running(Run {
            open: Some((_, _, touched)),
            ..
        }) = &mut state.phase
        {
            touched.insert(id);
        }
        Ok(estimate)
    }

    /// The amplitudes (length, ≥ 0) the host computed for point `id` in the open increment
    /// `kinc`, after querying its estimate there. A later report overwrites an earlier one.
    pub fn report(&self, id: i64, kinc: i32, amplitude: [f64; 2]) -> Result<(), StoreError> {
        if amplitude.iter().any(|a| !a.is_finite()) {
            return Err(StoreError::NonFinite("reported amplitude"));
        }
        if amplitude.iter().any(|&a| a < 0.0) {
            return Err(StoreError::OutOfRange("reported amplitude must be >= 0"));
        }
        self.check_point(id)?;
        let mut state = self.state()?;
        let (pass, sweep) = Self::current(&state, kinc)?;
        match state
            .records
            .get_mut(id as usize - 1)
            .and_then(|r| r.get_mut(&sweep))
        {
            Some(rec) if rec.estimate_pass == pass => {
                rec.reported = amplitude;
                rec.reported_pass = pass;
                Ok(())
            }
            _ => Err(seq(format!(
                "point {id} reported in increment {kinc} without an estimate queried there"
            ))),
        }
    }

    /// One UEXTERNALDB call. LOP 1/2 outside the sweep step are ignored.
    pub fn external_db(
        &self,
        lop: i32,
        lrestart: i32,
        kstep: i32,
        kinc: i32,
    ) -> Result<(), StoreError> {
        let in_sweep = self.config.sweep_step == 0 || kstep == self.config.sweep_step;
        match lop {
            0 => self.begin_pass(),
            1 if in_sweep => self.begin_increment(kinc),
            // All or nothing: when the restart data cannot be written, the store stays
            // where it was, so the host can retry the same LOP.
            2 if in_sweep => self.advance(|st| self.end_increment_in(st, kinc), lrestart >= 1),
            1 | 2 => Ok(()),
            3 => self.advance(|st| self.end_pass_in(st), true),
            4 => self.restore(),
            5 | 6 => {
                self.state()?.step = if lop == 5 { kstep } else { 0 };
                Ok(())
            }
            _ => Err(StoreError::OutOfRange("LOP must be 0..=6")),
        }
    }

    /// LOP 0: starts the pass the last decision asked for.
    pub fn begin_pass(&self) -> Result<(), StoreError> {
        let mut state = self.state()?;
        if let Phase::Running(run) = &state.phase {
            return Err(seq(format!(
                "pass {} is still running (LOP 3 missing)",
                run.number
            )));
        }
        let (kind, schedule) = match &state.next {
            Action::RunSweep => (PassKind::First, None),
            Action::RunPass(list) => (PassKind::Rerun, Some(list.clone())),
            Action::RunFinal(list) => (PassKind::Final, Some(list.clone())),
            Action::Done => return Err(seq("the iteration is done; no pass to start")),
            Action::Failed(_) => return Err(seq("the iteration failed; no pass to start")),
        };
        let number = u32::try_from(state.stats.len() + 1)
            .ok()
            .filter(|&n| n <= MAX_RESTART_PASSES)
            .ok_or_else(|| seq("no pass number left"))?;
        state.stats.push(PassStats {
            number,
            kind,
            increments_run: 0,
            increments_converged: 0,
            evaluations: 0,
            not_reported: 0,
        });
        state.phase = Phase::Running(Run {
            number,
            kind,
            schedule,
            open: None,
            ran: BTreeSet::new(),
        });
        Ok(())
    }

    /// LOP 1: opens increment `kinc` of the running pass. LOP 1 again for the open
    /// increment is a new attempt at it: Abaqus calls LOP 1 at the start of every attempt
    /// and LOP 2 only after one converged, so an increment it cuts back (no convergence,
    /// or PNEWDT < 1) is entered again with the same KINC. The failed attempt's queries
    /// are dropped; the new attempt's reports replace its reports.
    pub fn begin_increment(&self, kinc: i32) -> Result<(), StoreError> {
        let numbering = self.config.numbering;
        let mut state = self.state()?;
        let Phase::Running(run) = &mut state.phase else {
            return Err(seq("LOP 1 without a running pass (LOP 0 missing)"));
        };
        if let Some((open, _, _)) = &run.open {
            if *open != kinc {
                return Err(seq(format!(
                    "LOP 1 for {kinc} while increment {open} is open (LOP 2 missing)"
                )));
            }
        }
        let sweep = match (&run.schedule, numbering) {
            (None, _) => kinc,
            (Some(list), KincNumbering::Original) if list.contains(&kinc) => kinc,
            (Some(_), KincNumbering::Original) => {
                return Err(seq(format!(
                    "increment {kinc} is not scheduled in this pass"
                )))
            }
            (Some(list), KincNumbering::Sequential) => {
                match usize::try_from(kinc)
                    .ok()
                    .and_then(|i| list.get(i.wrapping_sub(1)))
                {
                    Some(&k) => k,
                    None => {
                        return Err(seq(format!(
                            "KINC {kinc} beyond the {} increments of this pass",
                            list.len()
                        )))
                    }
                }
            }
        };
        run.open = Some((kinc, sweep, BTreeSet::new()));
        Ok(())
    }

    /// LOP 2: compares estimate and computed amplitude of every point queried in the open
    /// increment; a point queried but not reported is not converged.
    pub fn end_increment(&self, kinc: i32) -> Result<(), StoreError> {
        self.advance(|st| self.end_increment_in(st, kinc), false)
    }

    fn end_increment_in(&self, state: &mut State, kinc: i32) -> Result<(), StoreError> {
        let Phase::Running(run) = &mut state.phase else {
            return Err(seq("LOP 2 without a running pass"));
        };
        let (sweep, touched) = match run.open.take() {
            Some((host, sweep, touched)) if host == kinc => (sweep, touched),
            Some(open) => {
                let msg = format!("LOP 2 for {kinc} but increment {} is open", open.0);
                run.open = Some(open);
                return Err(seq(msg));
            }
            None => return Err(seq(format!("LOP 2 for {kinc} without LOP 1"))),
        };
        let pass = run.number;
        run.ran.insert(sweep);
        let stats = state.stats.last_mut().expect("a running pass has stats");
        let mut all = true;
        for id in touched {
            let rec = state.records[id as usize - 1]
                .get_mut(&sweep)
                .expect("a queried point has a record");
            stats.evaluations = stats.evaluations.saturating_add(1);
            rec.passes = rec.passes.saturating_add(1);
            if rec.reported_pass != pass {
                rec.converged = false;
                rec.reason = Reason::NotReported;
                stats.not_reported = stats.not_reported.saturating_add(1);
            } else {
                let mut ok = true;
                for d in 0..rec.dirs {
                    let (a, a_star) = (rec.estimate[d], rec.reported[d]);
                    rec.history[d].push((a, a_star));
                    ok &= self.config.within(a, a_star);
                }
                rec.converged = ok;
                rec.reason = if ok {
                    Reason::None
                } else {
                    Reason::OutOfTolerance
                };
            }
            all &= rec.converged;
        }
        stats.increments_run = stats.increments_run.saturating_add(1);
        stats.increments_converged = stats
            .increments_converged
            .saturating_add(u32::from(all))
            .min(stats.increments_run);
        state.increments.insert(sweep, all);
        Ok(())
    }

    /// LOP 3: closes the pass and decides the next action.
    pub fn end_pass(&self) -> Result<(), StoreError> {
        self.advance(|st| self.end_pass_in(st), false)
    }

    fn end_pass_in(&self, state: &mut State) -> Result<(), StoreError> {
        let Phase::Running(run) = &state.phase else {
            return Err(seq("LOP 3 without a running pass"));
        };
        if let Some((open, _, _)) = &run.open {
            return Err(seq(format!("LOP 3 while increment {open} is open")));
        }
        if run.kind == PassKind::First && state.increments.is_empty() {
            state.phase = Phase::Ready;
            state.stats.pop();
            return Err(seq(
                "pass 1 ran no increment of the sweep step (check sweep_step)",
            ));
        }
        if let Some(schedule) = &run.schedule {
            // A scheduled increment the pass never ran is not converged (e.g. a final pass
            // that stopped early must not count as confirming it).
            for k in schedule {
                if !run.ran.contains(k) {
                    state.increments.insert(*k, false);
                }
            }
        }
        let kind = run.kind;
        state.phase = Phase::Ready;
        let left: Vec<i32> = state
            .increments
            .iter()
            .filter(|(_, &ok)| !ok)
            .map(|(&k, _)| k)
            .collect();
        if left.is_empty() {
            state.next = if kind == PassKind::Final {
                Action::Done
            } else {
                state.iteration_passes = state.iteration_passes.saturating_add(1);
                Action::RunFinal(state.increments.keys().copied().collect())
            };
            return Ok(());
        }
        state.iteration_passes = state.iteration_passes.saturating_add(1);
        state.next = if state.iteration_passes >= self.config.max_passes {
            Action::Failed(left)
        } else {
            Action::RunPass(left)
        };
        Ok(())
    }

    /// What to run next, with the number of the pass that would run (for `Done` and
    /// `Failed`: the last pass run). While a pass runs: `None`.
    pub fn next_action(&self) -> Result<Option<(Action, u32)>, StoreError> {
        let state = self.state()?;
        if let Phase::Running(_) = state.phase {
            return Ok(None);
        }
        let last = state.stats.len() as u32;
        let number = match state.next {
            Action::Done | Action::Failed(_) => last,
            _ => last + 1,
        };
        Ok(Some((state.next.clone(), number)))
    }

    /// Counts of pass `number` (1-based), if it was started.
    pub fn pass_stats(&self, number: u32) -> Result<Option<PassStats>, StoreError> {
        let state = self.state()?;
        Ok(number
            .checked_sub(1)
            .and_then(|i| state.stats.get(i as usize))
            .copied())
    }

    /// Number of passes started so far.
    pub fn passes(&self) -> Result<u32, StoreError> {
        Ok(self.state()?.stats.len() as u32)
    }

    /// Status of point `id` at sweep increment `kinc`; None when never queried there.
    pub fn point_status(&self, id: i64, kinc: i32) -> Result<Option<PointStatus>, StoreError> {
        self.check_point(id)?;
        let state = self.state()?;
        Ok(state
            .records
            .get(id as usize - 1)
            .and_then(|r| r.get(&kinc))
            .map(|r| PointStatus {
                estimate: r.estimate,
                computed: if r.reported_pass > 0 {
                    r.reported
                } else {
                    [0.0; 2]
                },
                directions: r.dirs,
                converged: r.converged,
                passes: r.passes,
                reason: r.reason,
            }))
    }

    /// Writes the store to the restart path (if any) atomically: a temporary file in the
    /// same directory, then a rename.
    pub fn save(&self) -> Result<(), StoreError> {
        let Some(path) = &self.config.restart_path else {
            return Ok(());
        };
        write_atomically(path, &self.serialize()?)
    }

    /// Applies `step` to the state; with `save` (and a restart path) only once the new
    /// state is in the restart file: on a write error the state stays as it was. A step
    /// that fails keeps what it changed (as without `save`) and writes nothing. Holds the
    /// registry (read) and the state during the write: LOP 2 and 3 run while no increment
    /// is open, so no per-point call waits on it.
    fn advance(
        &self,
        step: impl FnOnce(&mut State) -> Result<(), StoreError>,
        save: bool,
    ) -> Result<(), StoreError> {
        let path = match (&self.config.restart_path, save) {
            (Some(path), true) => path,
            _ => return step(&mut *self.state()?),
        };
        let registry = self.registry.read().map_err(|_| StoreError::Poisoned)?;
        let mut guard = self.state()?;
        let mut next = guard.clone();
        if let Err(e) = step(&mut next) {
            *guard = next;
            return Err(e);
        }
        let model = self.model()?;
        let fp = restart::Fingerprint {
            model: &model,
            config: &self.config,
        };
        write_atomically(
            path,
            &restart::write(&registry.keys, &registry.props, &next, &fp),
        )?;
        *guard = next;
        Ok(())
    }

    /// Replaces registry and iteration state by the restart file's content (LOP 4).
    pub fn restore(&self) -> Result<(), StoreError> {
        let Some(path) = &self.config.restart_path else {
            return Err(StoreError::Io("no restart path configured".into()));
        };
        let text = std::fs::read_to_string(path)
            .map_err(|e| StoreError::Io(format!("reading {}: {e}", path.display())))?;
        let model = self.model()?;
        let fp = restart::Fingerprint {
            model: &model,
            config: &self.config,
        };
        let (mut registry, state) = restart::parse(&text, &fp)?;
        registry.restored = !registry.keys.is_empty();
        *self.registry.write().map_err(|_| StoreError::Poisoned)? = registry;
        *self.state()? = state;
        Ok(())
    }

    fn serialize(&self) -> Result<String, StoreError> {
        let (keys, props) = {
            let reg = self.registry.read().map_err(|_| StoreError::Poisoned)?;
            (reg.keys.clone(), reg.props.clone())
        };
        let state = self.state()?.clone();
        let model = self.model()?;
        let fp = restart::Fingerprint {
            model: &model,
            config: &self.config,
        };
        Ok(restart::write(&keys, &props, &state, &fp))
    }
}

/// Writes `text` to `path` through a temporary file in the same directory and a rename,
/// so that the path holds the old or the new content, never a part.
fn write_atomically(path: &std::path::Path, text: &str) -> Result<(), StoreError> {
    let mut tmp = path.to_path_buf().into_os_string();
    tmp.push(format!(".tmp{}", std::process::id()));
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, text)
        .and_then(|_| std::fs::rename(&tmp, path))
        .map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            StoreError::Io(format!("writing {}: {e}", path.display()))
        })
}

mod config;
mod key;
mod ranks;
mod restart;

pub use config::{KincNumbering, StoreConfig, DEFAULT_MAX_PASSES, DEFAULT_RTOL, HISTORY_WINDOW};
pub use key::{props_checksum, PointKey, MAX_NAME_LEN};
pub use ranks::PassSummary;

#[cfg(test)]
mod tests;
