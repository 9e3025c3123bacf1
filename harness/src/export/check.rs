//! What a deck cannot express, as named errors before anything is built: lumped bodies,
//! springs and joints (a deck run reads solid elements only), contact features the
//! property table has no entry for (initial gap, area sub-grid), sweeps run downwards, harmonic balance, and physics switched off (a deck run
//! has every effect on). Study tables a deck does not carry are returned as notes.

use super::ExportError;
use crate::input::scene::{BodyKind, Scene};
use crate::settings::{Direction, Interval, Mode, SweepMethod};

/// Checks `scene`; returns the tables left out of the deck (study settings).
pub fn check(scene: &Scene) -> Result<Vec<String>, ExportError> {
    let s = &scene.spec;
    let err = |key: String, message: &str| ExportError::Unsupported {
        file: scene.file.clone(),
        key,
        message: message.to_string(),
    };
    if s.model.is_some() {
        return Err(err(
            "model".into(),
            "the scene's model is already a deck: run or edit that deck",
        ));
    }
    if !s.matrices.is_empty() {
        return Err(err(
            "matrices[0]".into(),
            "a model given by its matrices has no elements to write: its FE code has the deck",
        ));
    }
    if let Some(i) = s.bodies.iter().position(|b| b.kind == BodyKind::Mass) {
        return Err(err(
            format!("bodies[{i}].kind"),
            "a lumped mass: the exported deck holds solid elements only (a deck run reads no *MASS); model the body as a box",
        ));
    }
    if s.sweep.method == SweepMethod::Modal {
        return Err(err(
            "sweep.method".into(),
            "the modal route: the exported job is the UEXTERNALDB iteration over a DIRECT steady state (export the scene with method = \"direct\")",
        ));
    }
    if s.sweep.interval == Interval::Eigenfrequency {
        return Err(err(
            "sweep.interval".into(),
            "eigenfrequency intervals: the exported job lists its frequencies for a DIRECT steady state, which Abaqus divides by range",
        ));
    }
    if !s.springs.is_empty() {
        return Err(err(
            "springs".into(),
            "springs and dashpots on lumped masses have no solid-element equivalent",
        ));
    }
    if !s.joints.is_empty() {
        return Err(err(
            "joints".into(),
            "discrete joints between lumped masses have no solid-element equivalent",
        ));
    }
    for (i, f) in s.interfaces.iter().enumerate() {
        if f.initial_gap != 0.0 {
            return Err(err(
                format!("interfaces[{i}].initial_gap"),
                "the shim's property table has no initial gap (the deck's surfaces touch)",
            ));
        }
        if f.area_samples.is_some() {
            return Err(err(
                format!("interfaces[{i}].area_samples"),
                "UINTER evaluates the law at the slave node over its whole area; the sub-grid has no deck equivalent",
            ));
        }
    }
    if s.sweep.direction != Direction::Up {
        return Err(err(
            "sweep.direction".into(),
            "a deck's steady-state step is run upwards (each frequency from the previous one's state)",
        ));
    }
    if s.iteration.mode == Mode::HarmonicBalance {
        return Err(err(
            "iteration.mode".into(),
            "an Abaqus job iterates first-order k*, d* through UEXTERNALDB; harmonic balance has no deck equivalent",
        ));
    }
    let e = &s.effects;
    let damped = s
        .materials
        .values()
        .any(|m| m.rayleigh_alpha != 0.0 || m.rayleigh_beta != 0.0);
    let off = [
        (
            "normal_contact_nonlinearity",
            e.normal_contact_nonlinearity,
            true,
        ),
        ("tangential_microslip", e.tangential_microslip, true),
        ("macroslip", e.macroslip, true),
        ("contact_damping", e.contact_damping, true),
        ("material_damping", e.material_damping, damped),
    ];
    if let Some((name, _, _)) = off.iter().find(|(_, on, matters)| !on && *matters) {
        return Err(err(
            format!("effects.{name}"),
            "switched off: UINTER and a deck run have every effect on",
        ));
    }
    let mut notes = Vec::new();
    if s.time_domain.is_some() {
        notes.push("[time_domain] (settings of `jointlin run --time-domain`)".to_string());
    }
    if s.loss_study.is_some() {
        notes.push("[loss_study] (settings of `jointlin loss`)".to_string());
    }
    if e.point_energy_output || e.stick_slip_map {
        notes.push(
            "[effects] point_energy_output, stick_slip_map (report switches; the Abaqus job's per-point results are the state variables 52–57)"
                .to_string(),
        );
    }
    Ok(notes)
}
