//! The expression language of metrics written in scene files: arithmetic over four variables (the
//! coordinates) and named constants (a metric's parameters, `pi`), parsed once and compiled to a
//! flat postfix program that evaluates over any [`Scalar`](super::Scalar) — `f64`, or dual
//! numbers, whose derivatives are then exact.
//!
//! Grammar, loosest binding first (`^` and `**` are the same operator):
//!
//! ```text
//! sum     = product (("+" | "-") product)*
//! product = unary (("*" | "/") unary)*
//! unary   = ("-" | "+") unary | power
//! power   = atom (("^" | "**") unary)?        right-associative: 2^3^2 = 2^9, -r^2 = -(r^2)
//! atom    = number | name | name "(" sum ("," sum)? ")" | "(" sum ")"
//! ```
//!
//! Why a compiled program rather than a tree: a metric is evaluated a dozen times per integration
//! step, over dual numbers; a postfix program runs as one loop over a slice with its operands on a
//! fixed-size stack in registers or on the call stack, with no allocation and no pointer chasing
//! per evaluation. Parameters are known when the scene loads, so every constant sub-expression is
//! folded then, and operations with one constant operand (`2*M/r`, `1 - u`, `r^2`) compile to
//! single instructions taking the constant as an `f64` (a dual-by-real product costs a fifth of a
//! dual-by-dual one).
//!
//! Files: the functions and built-in constants in `functions`, the parser (text to a folded tree)
//! in `parser`, the compiled program and its evaluation in `program`.

use functions::{BINARY_FUNCTIONS, BUILT_IN_CONSTANTS, FUNCTIONS};

mod functions;
mod parser;
mod program;
#[cfg(test)]
mod tests;

pub(crate) use functions::atan2;
pub use program::Expression;

/// Whether `name` is taken by the language itself (a function or a built-in constant), so that a
/// parameter may not use it.
pub fn is_reserved(name: &str) -> bool {
    FUNCTIONS.iter().map(|f| f.0).chain(BINARY_FUNCTIONS.iter().map(|f| f.0)).any(|f| f == name)
        || BUILT_IN_CONSTANTS.iter().any(|c| c.0 == name)
}

/// Whether `name` can be written in an expression: a letter or `_`, then letters, digits and `_`.
pub fn is_name(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The names an expression may use: four variables (the coordinates, in order) and constants
/// (a metric's parameters; `pi` is always known).
#[derive(Clone, Copy, Debug)]
pub struct Names<'a> {
    pub variables: [&'a str; 4],
    pub constants: &'a [(&'a str, f64)],
}

/// Why an expression was rejected: what is wrong and where, as a byte offset into its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExpressionError {
    pub at: usize,
    pub message: String,
}

impl ExpressionError {
    fn new(at: usize, message: impl Into<String>) -> Self {
        Self { at, message: message.into() }
    }
}
