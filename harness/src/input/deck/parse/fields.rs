//! The fields of data lines: numbers, parameters, DOFs, face labels, frequency ranges.

use super::*;

pub(super) fn number(card: &Card, l: &DataLine, i: usize, what: &str) -> Result<f64, DeckError> {
    let f = l.fields.get(i).map(String::as_str).unwrap_or("");
    parse_number(f).ok_or_else(|| {
        card.error_at(
            l.line,
            K::Syntax,
            format!("{what}: {:?} is not a finite number", truncate(f)),
        )
    })
}

pub(super) fn opt_number(
    card: &Card,
    l: &DataLine,
    i: usize,
    what: &str,
    default: f64,
) -> Result<f64, DeckError> {
    match l.fields.get(i).map(|s| s.trim()) {
        None | Some("") => Ok(default),
        Some(_) => number(card, l, i, what),
    }
}

/// Whether a load card gives the imaginary part of a steady-state load (`IMAGINARY`;
/// `REAL`, the default, the real part). An `AMPLITUDE` is refused: a frequency-dependent
/// load would otherwise be read as constant.
pub(super) fn load_part(card: &Card) -> Result<bool, DeckError> {
    if let Some(a) = card.param("AMPLITUDE") {
        return Err(card.error(
            K::Unsupported,
            format!("AMPLITUDE={a}: a frequency-dependent load amplitude is not read (the data lines' values would be taken at every frequency)"),
        ));
    }
    choice(card, "OP", &["MOD"], "MOD")?;
    let (re, im) = (card.flag("REAL"), card.flag("IMAGINARY"));
    if re && im {
        return Err(card.error(
            K::BadValue,
            "REAL and IMAGINARY together: one card per part",
        ));
    }
    Ok(im)
}

/// The value of parameter `name`, upper case, one of `allowed` (`default` when the
/// card does not give it); another value is an error naming the ones implemented.
pub(super) fn choice(
    card: &Card,
    name: &str,
    allowed: &[&str],
    default: &str,
) -> Result<String, DeckError> {
    let Some(v) = card.param(name) else {
        return Ok(default.to_string());
    };
    let u = v.trim().to_ascii_uppercase();
    if allowed.contains(&u.as_str()) {
        return Ok(u);
    }
    Err(card.origin.error(
        K::Unsupported,
        &format!("{}, {name}=", card.name()),
        format!("{name}={v}: this reader implements {}", allowed.join(", ")),
    ))
}

pub(super) fn param_number(card: &Card, name: &str, default: f64) -> Result<f64, DeckError> {
    match card.param(name) {
        None => Ok(default),
        Some(v) => parse_number(v)
            .ok_or_else(|| card.error(K::Syntax, format!("{name}={v:?} is not a finite number"))),
    }
}

/// Data lines with at least one non-empty field.
pub(super) fn lines(card: &Card) -> impl Iterator<Item = &DataLine> {
    card.data
        .iter()
        .filter(|l| l.fields.iter().any(|f| !f.is_empty()))
}

/// DOF number 1…6.
pub(super) fn dof(card: &Card, l: &DataLine, i: usize) -> Result<u8, DeckError> {
    let f = l.fields.get(i).map(String::as_str).unwrap_or("");
    parse_id(f)
        .filter(|&d| d <= 6)
        .map(|d| d as u8)
        .ok_or_else(|| {
            card.error_at(
                l.line,
                K::BadValue,
                format!("DOF {:?} is not 1…6", truncate(f)),
            )
        })
}

/// Face label `S1`…`S6` / `P1`…`P6` → 0-based index.
pub(super) fn face_label(label: &str, letter: char) -> Option<usize> {
    let u = label.trim().to_ascii_uppercase();
    let n: usize = u.strip_prefix(letter)?.parse().ok()?;
    (1..=6).contains(&n).then(|| n - 1)
}

/// A `*STEADY STATE DYNAMICS` data line as Abaqus reads it: f_low, f_high (zero or
/// blank: the single frequency f_low), points (fewer than 2 or blank: 20), bias
/// (default `default_bias`: Abaqus's 1 for INTERVAL=RANGE, 3 for EIGENFREQUENCY).
pub(super) fn frequency_range(
    card: &Card,
    l: &DataLine,
    log: bool,
    default_bias: f64,
) -> Result<FrequencyRange, DeckError> {
    /// Abaqus's number of points when the line gives fewer than 2.
    const DEFAULT_POINTS: f64 = 20.0;
    let f_low = number(card, l, 0, "lower frequency")?;
    let f_high = opt_number(card, l, 1, "upper frequency", 0.0)?;
    if f_low.max(f_high) > MAX_FREQUENCY {
        return Err(card.error_at(
            l.line,
            K::BadValue,
            format!(
                "frequency {:e} above {MAX_FREQUENCY:e} (1/time): (2πf)² overflows",
                f_low.max(f_high)
            ),
        ));
    }
    if f_high == 0.0 {
        if f_low < 0.0 {
            return Err(card.error_at(l.line, K::BadValue, format!("frequency {f_low} < 0")));
        }
        return Ok(FrequencyRange {
            f_low,
            f_high: f_low,
            points: 1,
            bias: 1.0,
        });
    }
    let mut points = opt_number(card, l, 2, "number of points", DEFAULT_POINTS)?;
    if points < 2.0 {
        points = DEFAULT_POINTS;
    }
    let bias = opt_number(card, l, 3, "bias", default_bias)?;
    if f_low < 0.0 || f_high < f_low || points.fract() != 0.0 || points > 1e7 || bias <= 0.0 {
        return Err(card.error_at(l.line, K::BadValue, format!("need 0 <= f_low <= f_high, a whole number of points and bias > 0; got {f_low}, {f_high}, {points}, {bias}")));
    }
    if log && f_low <= 0.0 {
        return Err(card.error_at(
            l.line,
            K::BadValue,
            format!("f_low = {f_low} on a logarithmic scale (the default FREQUENCY SCALE): log spacing needs f_low > 0; give FREQUENCY SCALE=LINEAR or a positive f_low"),
        ));
    }
    Ok(FrequencyRange {
        f_low,
        f_high,
        points: points as usize,
        bias,
    })
}

#[cfg(test)]
mod tests {
    use super::face_label;

    #[test]
    fn face_labels_outside_one_to_six_are_no_face() {
        assert_eq!(face_label("S0", 'S'), None);
        assert_eq!(face_label("s7", 'S'), None);
        assert_eq!(face_label(" s6 ", 'S'), Some(5));
        assert_eq!(face_label("P1", 'P'), Some(0));
        assert_eq!(face_label("P1", 'S'), None);
    }
}
