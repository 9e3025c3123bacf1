//! What the plots share: the error message of a drawing, and the colours of their
//! series: Okabe and Ito's colour-blind-safe set (*Color Universal Design*, 2008)
//! without its yellow, which vanishes on white, and with a mid grey as the eighth.

use plotters::style::RGBColor;

/// Series colours in the order they are handed out.
pub const SERIES: [RGBColor; 8] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(230, 159, 0),   // orange
    RGBColor(0, 0, 0),       // black
    RGBColor(120, 120, 120), // grey
];

/// A plotters error as the message the plot writers return.
pub fn drawing_error<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// The colour of series `i` (the set repeats after eight).
pub fn series(i: usize) -> RGBColor {
    SERIES[i % SERIES.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_colour_stands_out_on_white() {
        // Relative luminance (sRGB, linearized) below 0.55: no yellow, no pale tint.
        let lin = |c: u8| {
            let c = c as f64 / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        for (i, c) in SERIES.iter().enumerate() {
            let l = 0.2126 * lin(c.0) + 0.7152 * lin(c.1) + 0.0722 * lin(c.2);
            assert!(l < 0.55, "colour {i} {c:?}: luminance {l:.2}");
        }
        assert_eq!(series(8), series(0));
    }
}
