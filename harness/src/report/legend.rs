//! Legends drawn beside a map: a vertical colour bar with its labelled ticks, and keys
//! (a symbol and what it means), in a narrow column of their own.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::style::drawing_error as err;

type Res = Result<(), String>;

/// Pixels: the bar's left edge, top, bottom and width.
const BAR: (i32, i32, i32, i32) = (20, 70, 400, 22);

/// A colour bar titled `title`: `colour(t)` for t from 0 (bottom) to 1 (top), with a
/// tick and label at each `(t, label)`.
pub fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    colour: &dyn Fn(f64) -> RGBColor,
    ticks: &[(f64, String)],
) -> Res {
    let (x, top, bottom, width) = BAR;
    let font = ("sans-serif", 13).into_font();
    area.draw(&Text::new(title.to_string(), (x, top - 25), font.clone()))
        .map_err(err)?;
    let steps = 80;
    for k in 0..steps {
        let y0 = bottom - (bottom - top) * (k + 1) / steps;
        let y1 = bottom - (bottom - top) * k / steps;
        let t = (k as f64 + 0.5) / steps as f64;
        area.draw(&Rectangle::new(
            [(x, y0), (x + width, y1)],
            colour(t).filled(),
        ))
        .map_err(err)?;
    }
    area.draw(&Rectangle::new([(x, top), (x + width, bottom)], BLACK))
        .map_err(err)?;
    for (t, label) in ticks {
        let y = bottom - (t.clamp(0.0, 1.0) * (bottom - top) as f64) as i32;
        area.draw(&PathElement::new(
            vec![(x + width, y), (x + width + 5, y)],
            BLACK,
        ))
        .map_err(err)?;
        area.draw(&Text::new(
            label.clone(),
            (x + width + 8, y - 6),
            font.clone(),
        ))
        .map_err(err)?;
    }
    Ok(())
}

/// Keys below the colour bar (or from its top when there is none), 28 px apart.
pub fn keys<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    below_bar: bool,
    items: &[(Symbol, &str)],
) -> Res {
    let (x, top, bottom, width) = BAR;
    let font = ("sans-serif", 13).into_font();
    let mut y = if below_bar { bottom + 30 } else { top };
    for (symbol, text) in items {
        let c = (x + width / 2, y + 7);
        match *symbol {
            Symbol::Frame => area.draw(&Rectangle::new(
                [(x, y), (x + width, y + 14)],
                BLACK.stroke_width(1),
            )),
            Symbol::Ring(r) => area.draw(&Circle::new(c, r, BLACK.stroke_width(2))),
            Symbol::Dot(r, colour) => area.draw(&Circle::new(c, r, colour.filled())),
        }
        .map_err(err)?;
        area.draw(&Text::new(
            text.to_string(),
            (x + width + 8, y),
            font.clone(),
        ))
        .map_err(err)?;
        y += 28;
    }
    Ok(())
}

/// What a key shows.
#[derive(Clone, Copy)]
pub enum Symbol {
    /// A black frame (a sliding cell of the stick/slip map).
    Frame,
    /// A black ring of this radius (px).
    Ring(i32),
    /// A filled dot of this radius (px) and colour.
    Dot(i32, RGBColor),
}
