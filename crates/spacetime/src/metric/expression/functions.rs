//! The language's functions and built-in constants, by the names expressions call them, and
//! their values over any [`Scalar`].

use crate::metric::user::Scalar;

/// One-argument functions, by the names expressions call them.
pub(super) const FUNCTIONS: &[(&str, Function)] = &[
    ("sqrt", Function::Sqrt),
    ("exp", Function::Exp),
    ("ln", Function::Ln),
    ("log", Function::Ln),
    ("sin", Function::Sin),
    ("cos", Function::Cos),
    ("tan", Function::Tan),
    ("asin", Function::Asin),
    ("acos", Function::Acos),
    ("atan", Function::Atan),
    ("sinh", Function::Sinh),
    ("cosh", Function::Cosh),
    ("tanh", Function::Tanh),
    ("abs", Function::Abs),
];

/// Two-argument functions.
pub(super) const BINARY_FUNCTIONS: &[(&str, Binary)] = &[("pow", Binary::Pow), ("atan2", Binary::Atan2)];

/// Constants every expression knows.
pub(super) const BUILT_IN_CONSTANTS: &[(&str, f64)] = &[("pi", std::f64::consts::PI)];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Function {
    Sqrt,
    Exp,
    Ln,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Abs,
}

impl Function {
    pub(super) fn apply<D: Scalar>(self, x: D) -> D {
        match self {
            Function::Sqrt => x.sqrt(),
            Function::Exp => x.exp(),
            Function::Ln => x.ln(),
            Function::Sin => x.sin(),
            Function::Cos => x.cos(),
            Function::Tan => x.tan(),
            Function::Asin => x.asin(),
            Function::Acos => x.acos(),
            Function::Atan => x.atan(),
            Function::Sinh => x.sinh(),
            Function::Cosh => x.cosh(),
            Function::Tanh => x.tanh(),
            Function::Abs => x.abs(),
        }
    }
}

/// The angle of the point `(x, y)`, `atan2(y, x)`, with derivatives exact to every order and finite
/// everywhere but the origin: the arctangent of the smaller coordinate over the larger plus a
/// constant of the quadrant. (`num_dual`'s own differentiates `atan(y/x)`, which is not finite
/// where `x = 0`: on the plane `z = 0`, for the polar angle `atan2(ρ, z)`.)
pub(crate) fn atan2<D: Scalar>(y: D, x: D) -> D {
    use std::f64::consts::{FRAC_PI_2, PI};
    let (yr, xr) = (y.re(), x.re());
    if xr.abs() >= yr.abs() {
        let base = (y / x).atan();
        match (xr < 0.0, yr < 0.0) {
            (false, _) => base,
            (true, false) => base + PI,
            (true, true) => base - PI,
        }
    } else {
        -(x / y).atan() + if yr < 0.0 { -FRAC_PI_2 } else { FRAC_PI_2 }
    }
}

/// Operators and functions of two operands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Binary {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    Atan2,
}

impl Binary {
    pub(super) fn apply<D: Scalar>(self, a: D, b: D) -> D {
        match self {
            Binary::Add => a + b,
            Binary::Sub => a - b,
            Binary::Mul => a * b,
            Binary::Div => a / b,
            Binary::Pow => a.powd(b),
            Binary::Atan2 => atan2(a, b),
        }
    }
}
