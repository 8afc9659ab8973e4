//! The wormhole of *Interstellar* ("Dneg" wormhole; James, von Tunzelmann, Franklin & Thorne
//! 2015, Am. J. Phys. 83, 486, eqs. (5)–(7)): a cylinder of radius `ρ` and length `2a`, whose
//! mouths open into asymptotically flat space like the outside of a mass `M`:
//! `r = ρ` for `|l| ≤ a`; beyond, with `x = 2(|l| − a)/(πM)`, `r = ρ + M [x arctan x − ½ ln(1 + x²)]`.
//! `dr/dl = (2/π) arctan x` is continuous at the mouths, `d²r/dl²` jumps there (`0` to
//! `4/(π²M)`): the shape is C¹. The paper's lensing width is `𝒲 = 1.42953 M`.

use super::super::descriptor::{
    exactly, non_negative, positive, MetricDescriptor, ParameterDescriptor, ParameterError, Range, THROAT,
};
use super::super::Spacetime;
use super::MorrisThorne;
use super::{Radius, Shape};
use std::f64::consts::{FRAC_2_PI, PI};

/// `𝒲/M`, the lensing width per mass parameter (James et al. 2015, below eq. (7)).
pub const LENSING_WIDTH_PER_MASS: f64 = 1.42953;

/// The *Interstellar* wormhole's shape: throat radius `ρ`, length `2a` of the cylindrical
/// interior, lensing width `𝒲 = 1.42953 M`. Valid for `ρ > 0`, `a ≥ 0`, `𝒲 > 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dneg {
    pub throat: f64,
    pub length: f64,
    pub lensing_width: f64,
}

/// The narrowest lensing width of the *Interstellar* wormhole, as a fraction of its throat.
pub const MIN_RELATIVE_LENSING_WIDTH: f64 = 1e-9;

/// `type = "wormhole"`: [`Spacetime::wormhole`].
pub static WORMHOLE: MetricDescriptor = MetricDescriptor {
    name: "wormhole",
    description:
        "the wormhole of *Interstellar*: a Morris–Thorne wormhole with a cylindrical interior (James et al. 2015)",
    parameters: &[
        THROAT,
        ParameterDescriptor {
            name: "length",
            meaning: "length 2a of the cylindrical interior",
            unit: "length",
            range: Range::NonNegative,
            default: Some(0.0),
            command_line_default: None,
        },
        ParameterDescriptor {
            name: "lensing_width",
            meaning: "lensing width 𝒲 of the mouths (the strongly lensed ring)",
            unit: "length",
            range: Range::Positive,
            default: None,
            command_line_default: None,
        },
    ],
    constraint: Some("lensing_width ≥ 10⁻⁹·throat"),
    oriented: false,
    build: |v| {
        let [throat, length, lensing_width] = exactly(v)?;
        Spacetime::wormhole(throat, length, lensing_width)
    },
    values: |s| {
        if let Spacetime::Wormhole(w) = s {
            let Dneg { throat, length, lensing_width } = w.shape;
            Some(vec![throat, length, lensing_width])
        } else {
            None
        }
    },
};

impl Spacetime {
    /// The wormhole of *Interstellar* (James et al. 2015): throat radius `throat > 0`, interior
    /// length `length ≥ 0`, lensing width `lensing_width ≥ 10⁻⁹ throat`.
    pub fn wormhole(throat: f64, length: f64, lensing_width: f64) -> Result<Self, ParameterError> {
        let throat = positive("throat", throat)?;
        let length = non_negative("length", length)?;
        let lensing_width = positive("lensing_width", lensing_width)?;
        // The shape function's `ln(1 + x²)`, with `x ∝ ℓ/𝒲`, overflows for widths near 10⁻¹⁵⁰ of
        // the distances a ray covers; long before, a narrower lensing region is a sharp edge that
        // rays cannot tell from one of 10⁻⁹ of the throat.
        let narrowest = MIN_RELATIVE_LENSING_WIDTH * throat;
        if !(lensing_width >= narrowest) {
            return Err(ParameterError::new(
                "lensing_width",
                format!(
                    "must be a finite number ≥ {narrowest:e} ({MIN_RELATIVE_LENSING_WIDTH:e} of the throat radius), \
                     got {lensing_width}: narrower is an edge no ray resolves in double precision"
                ),
            ));
        }
        Ok(Spacetime::Wormhole(MorrisThorne::new(Dneg::new(throat, length, lensing_width))))
    }
}

impl Dneg {
    pub fn new(throat: f64, length: f64, lensing_width: f64) -> Self {
        Self { throat, length, lensing_width }
    }

    /// The mass parameter `M = 𝒲/1.42953`.
    pub fn mass(&self) -> f64 {
        self.lensing_width / LENSING_WIDTH_PER_MASS
    }

    /// `a`, half the interior's length.
    fn half_length(&self) -> f64 {
        0.5 * self.length
    }
}

/// `ln(1 + x²)` for `x ≥ 0` without overflow.
fn ln_one_plus_square(x: f64) -> f64 {
    if x > 1.0 {
        2.0 * x.ln() + (1.0 / (x * x)).ln_1p()
    } else {
        (x * x).ln_1p()
    }
}

/// `f(x) = x arctan x − ½ ln(1 + x²)`: `f(0) = f'(0) = 0`, `f' = arctan x`, `f'' = 1/(1 + x²)`.
fn profile(x: f64) -> f64 {
    x * x.atan() - 0.5 * ln_one_plus_square(x)
}

impl Shape for Dneg {
    fn throat(&self) -> f64 {
        self.throat
    }

    /// `r − l dr/dl = ρ − ½M ln(1 + x²) − (2a/π) arctan x` beyond the mouths (`ρ` inside).
    fn radius(&self, l: f64) -> Radius {
        let (a, m) = (self.half_length(), self.mass());
        let beyond = l.abs() - a;
        if beyond <= 0.0 {
            return Radius { r: self.throat, slope: 0.0, intercept: self.throat };
        }
        let x = 2.0 * beyond / (PI * m);
        let turn = x.atan();
        Radius {
            r: self.throat + m * profile(x),
            slope: l.signum() * FRAC_2_PI * turn,
            intercept: self.throat - 0.5 * m * ln_one_plus_square(x) - a * FRAC_2_PI * turn,
        }
    }

    /// Newton's method on `f(x) = (rho − ρ)/M`: `f` is convex and increasing, so from the first
    /// iterate on every one lies above the root and they fall to it monotonically.
    fn proper_distance(&self, rho: f64) -> f64 {
        let (a, m) = (self.half_length(), self.mass());
        let target = (rho - self.throat) / m;
        if target <= 0.0 {
            return a;
        }
        let mut x = (2.0 * target).sqrt() + FRAC_2_PI * target;
        for _ in 0..100 {
            let next = x - (profile(x) - target) / x.atan();
            let done = (next - x).abs() <= 1e-15 * x;
            x = next;
            if done {
                break;
            }
        }
        a + 0.5 * PI * m * x
    }

    /// `r = |l| − a + ρ − M − M ln(2(|l| − a)/πM) + O(1/l²)`: `μ = M`.
    fn log_coefficient(&self) -> f64 {
        self.mass()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn interstellar() -> Dneg {
        Dneg::new(1.0, 0.01, 0.05)
    }

    #[test]
    fn radius_is_c1_at_the_mouths_and_its_slope_and_intercept_match_differences() {
        for shape in [interstellar(), Dneg::new(2.0, 3.0, 1.2), Dneg::new(1.0, 0.0, 0.5)] {
            let a = shape.half_length();
            for l in [-40.0, -a - 0.3, -a - 1e-3, 0.5 * a, a + 1e-4, a + 0.2, a + 5.0, 1e3, 1e8] {
                let h = 1e-6 * (1.0 + l.abs());
                let fd = (shape.radius(l + h).r - shape.radius(l - h).r) / (2.0 * h);
                let at = shape.radius(l);
                assert!((at.slope - fd).abs() < 1e-6, "{shape:?} l = {l}: slope {} vs {fd}", at.slope);
                let intercept = at.r - l * at.slope;
                assert!((at.intercept - intercept).abs() < 1e-9 * (1.0 + at.r), "l = {l}: {}", at.intercept);
            }
            let (inside, outside) = (shape.radius(a - 1e-12), shape.radius(a + 1e-12));
            assert!((inside.r - outside.r).abs() < 1e-12 && outside.slope.abs() < 1e-10, "C¹ at the mouth");
        }
    }

    #[test]
    fn proper_distance_inverts_the_radius() {
        for shape in [interstellar(), Dneg::new(2.0, 3.0, 1.2), Dneg::new(1.0, 0.0, 0.5)] {
            assert_eq!(shape.proper_distance(shape.throat), shape.half_length());
            for l in [1e-6, 0.01, 0.3, 2.0, 17.0, 1e4, 1e9] {
                let l = shape.half_length() + l;
                let rho = shape.radius(l).r;
                let found = shape.proper_distance(rho);
                assert!((found - l).abs() < 1e-9 * l.max(1.0), "{shape:?}: l = {l}, found {found}");
            }
        }
    }

    /// Far out the wormhole looks like flat space seen from the mouth, shifted by a logarithm:
    /// `r = |l| − a + ρ − M − M ln x + O(1/x²)` (the expansion of eq. (5)).
    #[test]
    fn far_radius_follows_the_expansion() {
        let shape = Dneg::new(1.0, 0.4, 0.3);
        let (a, m) = (0.2, shape.mass());
        for l in [1e3, 1e6] {
            let x = 2.0 * (l - a) / (PI * m);
            let expect = l - a + 1.0 - m - m * x.ln();
            assert!((shape.radius(l).r - expect).abs() < 2.0 * m / (x * x) + 1e-12 * l, "l = {l}");
        }
    }
}
