//! Tests of the expression language: precedence, folding, derivatives, errors and names.

use super::program::Op;
use super::{atan2, is_name, is_reserved, Expression, ExpressionError, Names};
use num_dual::Dual64;

const NAMES: Names<'static> = Names { variables: ["t", "r", "theta", "phi"], constants: &[("M", 1.5), ("Q", 0.5)] };

fn eval(text: &str, vars: [f64; 4]) -> f64 {
    Expression::compile(text, NAMES).unwrap_or_else(|e| panic!("{text}: {e:?}")).eval(&vars)
}

fn error(text: &str) -> ExpressionError {
    Expression::compile(text, NAMES).expect_err(text)
}

#[test]
fn precedence_and_associativity() {
    let v = [0.0, 2.0, 0.5, 3.0];
    for (text, expect) in [
        ("1 + 2*3", 7.0),
        ("(1 + 2)*3", 9.0),
        ("2^3^2", 512.0),
        ("2**3**2", 512.0),
        ("-r^2", -4.0),
        ("(-r)^2", 4.0),
        ("2^-1", 0.5),
        ("r - 1 - 1", 0.0),
        ("12 / r / 3", 2.0),
        ("- -r", 2.0),
        ("+r", 2.0),
        ("1.5e1 + .5 + 2.E-1", 15.7),
        ("-(1 - 2*M/r)", -(1.0 - 2.0 * 1.5 / 2.0)),
        ("r^2*sin(theta)^2", 4.0 * 0.5f64.sin().powi(2)),
        ("atan2(r, phi) + pow(r, 0.5)", 2.0f64.atan2(3.0) + 2f64.sqrt()),
        ("ln(exp(phi)) + log(1) + abs(-r)", 5.0),
        ("cos(pi) + sqrt(r*r) + tan(0) + sinh(0) + cosh(0) + tanh(0)", 2.0),
        ("asin(1) + acos(1) + atan(0)", std::f64::consts::FRAC_PI_2),
        ("r^phi", 8.0),
        ("M^2 - Q^2", 2.0),
        ("t", 0.0),
    ] {
        let got = eval(text, v);
        assert!((got - expect).abs() < 1e-14 * expect.abs().max(1.0), "{text}: {got} vs {expect}");
    }
}

/// Constants fold at compile time and one-constant operations take the constant inline:
/// `-(1 - 2*M/r)` is five instructions.
#[test]
fn constants_fold() {
    let e = Expression::compile("-(1 - 2*M/r) + 0*(2 + 3)", NAMES).unwrap();
    assert_eq!(e.ops, vec![Op::Var(1), Op::DivIntoC(3.0), Op::SubFromC(1.0), Op::Neg, Op::AddC(0.0)]);
    assert!(e.reads(1) && !e.reads(0) && !e.reads(2));
    assert_eq!(Expression::compile("M*Q*pi", NAMES).unwrap().ops, vec![Op::Const(0.75 * std::f64::consts::PI)]);
}

/// Dual numbers give exact derivatives through every instruction.
#[test]
fn derivatives_are_exact() {
    let text = "-(1 - 2*M/r) + r^2*sin(theta)^2 / (1 + r) + pow(r, theta) + atan2(theta, r) - 3/r + r^1.5";
    let e = Expression::compile(text, NAMES).unwrap();
    let (r, th) = (2.3, 0.7);
    let f = |r: f64| e.eval(&[0.0, r, th, 0.0]);
    let d = e.eval(&[Dual64::from(0.0), Dual64::from_re(r).derivative(), Dual64::from(th), Dual64::from(0.0)]);
    let h = 1e-6;
    let fd = (f(r + h) - f(r - h)) / (2.0 * h);
    assert!((d.re - f(r)).abs() < 1e-15);
    assert!((d.eps - fd).abs() < 1e-8, "{} vs {fd}", d.eps);
}

#[test]
fn errors_point_into_the_text() {
    let cases = [
        ("1 - 2*M/rr", 8, "unknown name \"rr\""),
        ("1 + ", 4, "unexpected end of expression"),
        ("(1 + r", 6, "expected ')' to close the '(' at column 1"),
        ("sqrt(r, 2)", 6, "sqrt takes one argument"),
        ("pow(r)", 0, "pow takes two arguments"),
        ("foo(r)", 0, "unknown function \"foo\""),
        ("sin + 1", 0, "sin is a function"),
        ("r / 0", 2, "division by zero"),
        ("1 / (1 - 1)", 2, "no finite value"),
        ("sqrt(-1) * r", 0, "no finite value"),
        ("r 2", 2, "unexpected '2'"),
        ("r # 2", 2, "unexpected '#'"),
        ("2*θ", 2, "unexpected 'θ'"),
    ];
    for (text, at, message) in cases {
        let e = error(text);
        assert_eq!(e.at, at, "{text}: {e:?}");
        assert!(e.message.contains(message), "{text}: {e:?}");
    }
    let deep = format!("{}r{}", "(".repeat(200), ")".repeat(200));
    assert!(error(&deep).message.contains("nested more than"));
    let tall = "r*(".repeat(80) + "r" + &")".repeat(80);
    assert!(error(&tall).message.contains("too deeply nested"), "{:?}", error(&tall));
}

/// `atan2` in every quadrant and on the axes, with its derivative `(x dy − y dx)/(x² + y²)`.
#[test]
fn atan2_everywhere() {
    for (y, x) in [
        (1.0, 2.0),
        (2.0, 1.0),
        (2.0, -1.0),
        (1.0, -2.0),
        (-1.0, -2.0),
        (-2.0, -1.0),
        (-2.0, 1.0),
        (0.0, 1.0),
        (1.0, 0.0),
        (0.0, -1.0),
        (-1.0, 0.0),
        (3.0, 3.0),
    ] {
        let a = atan2(Dual64::from_re(y).derivative(), Dual64::from_re(x));
        let b = atan2(Dual64::from_re(y), Dual64::from_re(x).derivative());
        assert!((a.re - f64::atan2(y, x)).abs() < 1e-15, "({y}, {x})");
        assert!(
            (a.eps - x / (x * x + y * y)).abs() < 1e-15 && (b.eps + y / (x * x + y * y)).abs() < 1e-15,
            "({y}, {x})"
        );
    }
}

#[test]
fn names() {
    assert!(is_name("M") && is_name("_q2") && !is_name("2q") && !is_name("a-b") && !is_name(""));
    assert!(is_reserved("pi") && is_reserved("sqrt") && is_reserved("atan2") && !is_reserved("M"));
}

/// The stack height counted at compile time is what evaluation uses: a right-leaning chain
/// needs one more slot per level.
#[test]
fn stack_depth() {
    let e = Expression::compile("r*(theta + r*(phi + r*(t + r)))", NAMES).unwrap();
    assert_eq!(e.depth, 7);
    assert_eq!(e.eval(&[1.0, 2.0, 3.0, 4.0]), 2.0 * (3.0 + 2.0 * (4.0 + 2.0 * (1.0 + 2.0))));
}
