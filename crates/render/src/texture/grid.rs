//! # Grid (`type = "grid"`)
//!
//! Straight lines on a background — the poster's back wall: a white wall ruled with a square grid of dark
//! lines, a few of them coloured so that their lensed images can be told apart (Ayush & Chaudhuri 2017,
//! fig. 1). In the scaled coordinates `st`, lines of constant `s` sit at `s = k·spacing` and lines of
//! constant `t` at `t = k·spacing` (`k` any integer), each `width` wide (centred on the line).
//!
//! A *highlight* recolours one line: `axis = "u"` picks the line of constant `u` (it runs along `v`) at
//! `u = index·spacing` (in scaled units); `axis = "v"` the line of constant `v`. Where two highlighted
//! lines cross, the one listed first wins; highlighted lines are drawn over ordinary ones.
//!
//! | parameter    | type                | default          | meaning                                      |
//! |--------------|---------------------|------------------|----------------------------------------------|
//! | `background` | colour              | `[0.9, 0.9, 0.9]`| between the lines                            |
//! | `line`       | colour              | `[0.05, 0.05, 0.05]` | ordinary lines                           |
//! | `spacing`    | number > 0          | 0.1              | distance between lines, in units of `st`     |
//! | `width`      | number ≥ 0          | 0.01             | line width, in units of `st`                 |
//! | `highlights` | array of tables     | `[]`             | `{ axis = "u" or "v", index = k, colour }`   |
//! | `uv_scale`   | `[su, sv]`          | `[1, 1]`         | `st = (u·su, v·sv)`                          |
//!
//! ```toml
//! [objects.material]
//! type = "diffuse"
//! [objects.material.reflectance]
//! type = "grid"
//! background = [0.9, 0.9, 0.9]
//! line = [0.05, 0.05, 0.05]
//! uv_scale = [8, 4]        # an 8 m × 4 m wall with uv in [0, 1]²: st in metres
//! spacing = 0.25
//! width = 0.02
//! highlights = [
//!   { axis = "v", index = 10, colour = [0.8, 0.05, 0.05] },   # a red horizontal line at 2.5 m
//!   { axis = "u", index = 20, colour = [0.05, 0.6, 0.05] },   # a green vertical line at 5 m
//! ]
//! ```

use crate::rgb::Rgb;

/// Which family a highlighted line belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GridAxis {
    /// A line of constant `u` (it runs along `v`).
    U,
    /// A line of constant `v` (it runs along `u`).
    V,
}

/// One recoloured grid line: the line of constant `axis` at `index · spacing`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridHighlight {
    pub axis: GridAxis,
    pub index: i64,
    pub colour: Rgb,
}

/// The grid's colour at scaled coordinates `st`. A non-positive or non-finite `spacing` draws no lines.
pub fn eval(st: [f64; 2], background: Rgb, line: Rgb, spacing: f64, width: f64, highlights: &[GridHighlight]) -> Rgb {
    if !(spacing > 0.0 && spacing.is_finite()) {
        return background;
    }
    let half = 0.5 * width;
    // The nearest line of each family and whether `st` lies on it.
    let nearest = |x: f64| {
        let k = (x / spacing).round();
        ((x - k * spacing).abs() <= half, k as i64)
    };
    let (on_u, ku) = nearest(st[0]);
    let (on_v, kv) = nearest(st[1]);
    if !on_u && !on_v {
        return background;
    }
    highlights
        .iter()
        .find(|h| match h.axis {
            GridAxis::U => on_u && h.index == ku,
            GridAxis::V => on_v && h.index == kv,
        })
        .map_or(line, |h| h.colour)
}

#[cfg(test)]
mod tests {
    use super::*;

    const BG: Rgb = Rgb::ONE;
    const LINE: Rgb = Rgb::ZERO;
    const RED: Rgb = Rgb::new(1.0, 0.0, 0.0);
    const GREEN: Rgb = Rgb::new(0.0, 1.0, 0.0);

    fn wall(st: [f64; 2]) -> Rgb {
        let highlights = [
            GridHighlight { axis: GridAxis::V, index: 3, colour: RED },
            GridHighlight { axis: GridAxis::U, index: -2, colour: GREEN },
        ];
        eval(st, BG, LINE, 0.5, 0.04, &highlights)
    }

    #[test]
    fn lines_at_multiples_of_spacing() {
        assert_eq!(wall([0.25, 0.25]), BG, "cell centre");
        assert_eq!(wall([0.5, 0.25]), LINE, "on u = 0.5");
        assert_eq!(wall([0.519, 0.25]), LINE, "inside the half width 0.02");
        assert_eq!(wall([0.521, 0.25]), BG, "just outside");
        assert_eq!(wall([0.25, -0.99]), LINE, "on v = -1, negative side");
        assert_eq!(wall([1.0, 1.0]), LINE, "crossing");
    }

    #[test]
    fn highlights_recolour_their_line_only() {
        assert_eq!(wall([0.25, 1.5]), RED, "v line 3 is at v = 1.5");
        assert_eq!(wall([0.25, 1.0]), LINE, "v line 2 is ordinary");
        assert_eq!(wall([-1.0, 0.25]), GREEN, "u line -2 is at u = -1");
        assert_eq!(wall([1.0, 0.25]), LINE, "u line +2 is ordinary");
        assert_eq!(wall([-1.0, 1.5]), RED, "crossing of two highlights: first listed wins");
        assert_eq!(wall([0.5, 1.5]), RED, "highlight drawn over an ordinary crossing line");
        assert_eq!(wall([-0.9, 1.2]), BG);
    }

    #[test]
    fn degenerate_spacing_draws_nothing() {
        for spacing in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(eval([0.0, 0.0], BG, LINE, spacing, 0.1, &[]), BG);
        }
    }
}
