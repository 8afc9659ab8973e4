//! The compiled form of an expression: a flat postfix program over the variables, with the
//! operations that take one constant operand specialised (module documentation of [`super`]),
//! and its evaluation over any [`Scalar`].

use super::functions::{Binary, Function};
use super::parser::{Node, Parser};
use super::{ExpressionError, Names};
use crate::metric::user::Scalar;

/// The most operands an expression may hold pending at once while it is evaluated (the height of
/// its evaluation stack); an expression needing more is rejected when it is compiled.
const MAX_STACK: usize = 64;

/// A compiled expression: a postfix program over the variables, constants folded.
#[derive(Clone, Debug, PartialEq)]
pub struct Expression {
    pub(super) ops: Vec<Op>,
    /// The height of the evaluation stack the program needs.
    pub(super) depth: usize,
    /// Which of the four variables it reads.
    reads: [bool; 4],
}

/// One instruction of the postfix program. The `…C` forms take a constant operand inline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Op {
    Const(f64),
    Var(usize),
    Neg,
    Call(Function),
    Binary(Binary),
    /// `x + c`.
    AddC(f64),
    /// `x · c`.
    MulC(f64),
    /// `c − x`.
    SubFromC(f64),
    /// `c / x`.
    DivIntoC(f64),
    /// `x^n`, `n` a small integer.
    Powi(i32),
    /// `x^c`.
    Powf(f64),
}

impl Expression {
    /// Parses and compiles `text` over `names`.
    pub fn compile(text: &str, names: Names<'_>) -> Result<Expression, ExpressionError> {
        let mut parser = Parser { text, names, pos: 0, nesting: 0 };
        let tree = parser.sum()?;
        parser.skip_space();
        if parser.pos < text.len() {
            let found = parser.describe_here();
            return Err(ExpressionError::new(parser.pos, format!("unexpected {found}: expected an operator")));
        }
        let mut out = Expression { ops: Vec::new(), depth: 0, reads: [false; 4] };
        let mut height = 0;
        out.emit(&tree, &mut height);
        if out.depth > MAX_STACK {
            return Err(ExpressionError::new(
                0,
                format!("too deeply nested to evaluate (needs {} pending values; at most {MAX_STACK})", out.depth),
            ));
        }
        Ok(out)
    }

    /// Whether the expression reads variable `index` (0 to 3).
    pub fn reads(&self, index: usize) -> bool {
        self.reads[index]
    }

    /// The value at `vars`.
    #[inline]
    pub fn eval<D: Scalar>(&self, vars: &[D; 4]) -> D {
        // A stack no taller than needed: its initialisation is a cost of every evaluation.
        match self.depth {
            0..=4 => self.run::<D, 4>(vars),
            5..=8 => self.run::<D, 8>(vars),
            9..=16 => self.run::<D, 16>(vars),
            _ => self.run::<D, MAX_STACK>(vars),
        }
    }

    #[inline]
    fn run<D: Scalar, const N: usize>(&self, vars: &[D; 4]) -> D {
        let mut stack = [D::from(0.0); N];
        let mut top = 0;
        for op in &self.ops {
            match *op {
                Op::Const(c) => {
                    stack[top] = D::from(c);
                    top += 1;
                }
                Op::Var(i) => {
                    stack[top] = vars[i];
                    top += 1;
                }
                Op::Binary(b) => {
                    top -= 1;
                    stack[top - 1] = b.apply(stack[top - 1], stack[top]);
                }
                Op::Neg => stack[top - 1] = -stack[top - 1],
                Op::Call(f) => stack[top - 1] = f.apply(stack[top - 1]),
                Op::AddC(c) => stack[top - 1] += c,
                Op::MulC(c) => stack[top - 1] *= c,
                Op::SubFromC(c) => stack[top - 1] = -stack[top - 1] + c,
                Op::DivIntoC(c) => stack[top - 1] = stack[top - 1].recip() * c,
                Op::Powi(n) => stack[top - 1] = stack[top - 1].powi(n),
                Op::Powf(c) => stack[top - 1] = stack[top - 1].powf(c),
            }
        }
        stack[0]
    }

    fn push(&mut self, op: Op, height: &mut usize, change: isize) {
        self.ops.push(op);
        *height = height.wrapping_add_signed(change);
        self.depth = self.depth.max(*height);
    }

    /// Appends the program of `node`, specialising operations with one constant operand.
    fn emit(&mut self, node: &Node, height: &mut usize) {
        match node {
            Node::Num(c) => self.push(Op::Const(*c), height, 1),
            Node::Var(i) => {
                self.reads[*i] = true;
                self.push(Op::Var(*i), height, 1);
            }
            Node::Neg(a) => {
                self.emit(a, height);
                self.push(Op::Neg, height, 0);
            }
            Node::Call(f, a) => {
                self.emit(a, height);
                self.push(Op::Call(*f), height, 0);
            }
            Node::Binary(b, l, r) => {
                let op = match (b, l.as_ref(), r.as_ref()) {
                    (Binary::Add, x, Node::Num(c)) | (Binary::Add, Node::Num(c), x) => Some((x, Op::AddC(*c))),
                    (Binary::Sub, x, Node::Num(c)) => Some((x, Op::AddC(-c))),
                    (Binary::Sub, Node::Num(c), x) => Some((x, Op::SubFromC(*c))),
                    (Binary::Mul, x, Node::Num(c)) | (Binary::Mul, Node::Num(c), x) => Some((x, Op::MulC(*c))),
                    (Binary::Div, x, Node::Num(c)) => Some((x, Op::MulC(1.0 / c))),
                    (Binary::Div, Node::Num(c), x) => Some((x, Op::DivIntoC(*c))),
                    (Binary::Pow, x, Node::Num(c)) if c.fract() == 0.0 && c.abs() <= 1024.0 => {
                        Some((x, Op::Powi(*c as i32)))
                    }
                    (Binary::Pow, x, Node::Num(c)) => Some((x, Op::Powf(*c))),
                    _ => None,
                };
                match op {
                    Some((x, op)) => {
                        self.emit(x, height);
                        self.push(op, height, 0);
                    }
                    None => {
                        self.emit(l, height);
                        self.emit(r, height);
                        self.push(Op::Binary(*b), height, -1);
                    }
                }
            }
        }
    }
}
