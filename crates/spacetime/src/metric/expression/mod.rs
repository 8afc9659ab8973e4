//! The expression language of metrics written in scene files: arithmetic over four variables (the
//! coordinates) and named constants (a metric's parameters, `pi`), parsed once and compiled to a
//! flat postfix program that evaluates over any [`Scalar`] — `f64`, or dual numbers, whose
//! derivatives are then exact.
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

use super::user::Scalar;

/// The deepest nesting of parentheses, unary signs and function calls accepted: far beyond any
/// metric, and a bound on the parser's recursion over untrusted text.
const MAX_NESTING: usize = 100;

/// The most operands an expression may hold pending at once while it is evaluated (the height of
/// its evaluation stack); an expression needing more is rejected when it is compiled.
const MAX_STACK: usize = 64;

/// One-argument functions, by the names expressions call them.
const FUNCTIONS: &[(&str, Function)] = &[
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
const BINARY_FUNCTIONS: &[(&str, Binary)] = &[("pow", Binary::Pow), ("atan2", Binary::Atan2)];

/// Constants every expression knows.
const BUILT_IN_CONSTANTS: &[(&str, f64)] = &[("pi", std::f64::consts::PI)];

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

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Function {
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
    fn apply<D: Scalar>(self, x: D) -> D {
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
enum Binary {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    Atan2,
}

impl Binary {
    fn apply<D: Scalar>(self, a: D, b: D) -> D {
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

/// A compiled expression: a postfix program over the variables, constants folded.
#[derive(Clone, Debug, PartialEq)]
pub struct Expression {
    ops: Vec<Op>,
    /// The height of the evaluation stack the program needs.
    depth: usize,
    /// Which of the four variables it reads.
    reads: [bool; 4],
}

/// One instruction of the postfix program. The `…C` forms take a constant operand inline.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Op {
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

/// The parsed expression, constants already folded.
enum Node {
    Num(f64),
    Var(usize),
    Neg(Box<Node>),
    Call(Function, Box<Node>),
    Binary(Binary, Box<Node>, Box<Node>),
}

/// Folds an operation on constants, which must give a finite number; else builds the node.
fn binary(b: Binary, l: Node, r: Node, at: usize) -> Result<Node, ExpressionError> {
    if let (Node::Num(x), Node::Num(y)) = (&l, &r) {
        return finite(b.apply(*x, *y), at);
    }
    if b == Binary::Div && matches!(r, Node::Num(c) if c == 0.0) {
        return Err(ExpressionError::new(at, "division by zero"));
    }
    Ok(Node::Binary(b, Box::new(l), Box::new(r)))
}

fn finite(v: f64, at: usize) -> Result<Node, ExpressionError> {
    if v.is_finite() {
        Ok(Node::Num(v))
    } else {
        Err(ExpressionError::new(at, format!("this part has no finite value (it evaluates to {v})")))
    }
}

/// A recursive-descent parser over the text, one method per rule of the grammar.
struct Parser<'a> {
    text: &'a str,
    names: Names<'a>,
    pos: usize,
    nesting: usize,
}

impl Parser<'_> {
    fn skip_space(&mut self) {
        while self.text[self.pos..].starts_with(|c: char| c.is_whitespace()) {
            self.pos += self.text[self.pos..].chars().next().map_or(1, char::len_utf8);
        }
    }

    /// After spaces, whether the text continues with `token` (then consumed).
    fn eat(&mut self, token: &str) -> bool {
        self.skip_space();
        if self.text[self.pos..].starts_with(token) {
            self.pos += token.len();
            true
        } else {
            false
        }
    }

    /// What comes next, for messages: "end of expression" or the character, quoted.
    fn describe_here(&self) -> String {
        match self.text[self.pos..].chars().next() {
            None => "end of expression".to_string(),
            Some(c) => format!("'{c}'"),
        }
    }

    /// Enters one level of nesting, refusing text nested beyond [`MAX_NESTING`].
    fn nest(&mut self) -> Result<(), ExpressionError> {
        self.nesting += 1;
        if self.nesting > MAX_NESTING {
            return Err(ExpressionError::new(self.pos, format!("nested more than {MAX_NESTING} deep")));
        }
        Ok(())
    }

    fn sum(&mut self) -> Result<Node, ExpressionError> {
        let mut left = self.product()?;
        loop {
            self.skip_space();
            let at = self.pos;
            let op = if self.eat("+") {
                Binary::Add
            } else if self.eat("-") {
                Binary::Sub
            } else {
                return Ok(left);
            };
            left = binary(op, left, self.product()?, at)?;
        }
    }

    fn product(&mut self) -> Result<Node, ExpressionError> {
        let mut left = self.unary()?;
        loop {
            self.skip_space();
            let at = self.pos;
            if self.text[self.pos..].starts_with("**") {
                return Ok(left);
            }
            let op = if self.eat("*") {
                Binary::Mul
            } else if self.eat("/") {
                Binary::Div
            } else {
                return Ok(left);
            };
            left = binary(op, left, self.unary()?, at)?;
        }
    }

    fn unary(&mut self) -> Result<Node, ExpressionError> {
        self.nest()?;
        let node = if self.eat("-") {
            match self.unary()? {
                Node::Num(c) => Node::Num(-c),
                n => Node::Neg(Box::new(n)),
            }
        } else if self.eat("+") {
            self.unary()?
        } else {
            self.power()?
        };
        self.nesting -= 1;
        Ok(node)
    }

    fn power(&mut self) -> Result<Node, ExpressionError> {
        let base = self.atom()?;
        self.skip_space();
        let at = self.pos;
        if self.eat("**") || self.eat("^") {
            return binary(Binary::Pow, base, self.unary()?, at);
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Node, ExpressionError> {
        self.skip_space();
        let start = self.pos;
        let rest = &self.text[start..];
        if self.eat("(") {
            let inner = self.sum()?;
            self.close(start)?;
            return Ok(inner);
        }
        if rest.starts_with(|c: char| c.is_ascii_digit() || c == '.') {
            return self.number();
        }
        let len = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(rest.len());
        if len == 0 || !is_name(&rest[..len]) {
            let found = self.describe_here();
            return Err(ExpressionError::new(start, format!("unexpected {found}: expected a number, a name or '('")));
        }
        let name = &rest[..len];
        self.pos += len;
        if self.eat("(") {
            return self.call(name, start);
        }
        self.name(name, start)
    }

    /// The `)` closing the parenthesis opened at `open`.
    fn close(&mut self, open: usize) -> Result<(), ExpressionError> {
        if self.eat(")") {
            return Ok(());
        }
        let found = self.describe_here();
        Err(ExpressionError::new(
            self.pos,
            format!("expected ')' to close the '(' at column {}, found {found}", open + 1),
        ))
    }

    /// A decimal number: digits, an optional fraction and an optional exponent.
    fn number(&mut self) -> Result<Node, ExpressionError> {
        let start = self.pos;
        let bytes = self.text.as_bytes();
        let digits = |mut i: usize| {
            while i < bytes.len() && bytes[i].is_ascii_digit() {
                i += 1;
            }
            i
        };
        let mut end = digits(start);
        if end < bytes.len() && bytes[end] == b'.' {
            end = digits(end + 1);
        }
        if end < bytes.len() && (bytes[end] == b'e' || bytes[end] == b'E') {
            let mut exp = end + 1;
            if exp < bytes.len() && (bytes[exp] == b'+' || bytes[exp] == b'-') {
                exp += 1;
            }
            if exp < bytes.len() && bytes[exp].is_ascii_digit() {
                end = digits(exp);
            }
        }
        let lexeme = &self.text[start..end];
        self.pos = end;
        match lexeme.parse::<f64>() {
            Ok(v) => finite(v, start),
            Err(_) => Err(ExpressionError::new(start, format!("\"{lexeme}\" is not a number"))),
        }
    }

    /// A variable or a constant.
    fn name(&self, name: &str, at: usize) -> Result<Node, ExpressionError> {
        if let Some(i) = self.names.variables.iter().position(|v| *v == name) {
            return Ok(Node::Var(i));
        }
        let constants = self.names.constants.iter().chain(BUILT_IN_CONSTANTS);
        if let Some((_, v)) = constants.clone().find(|c| c.0 == name) {
            return Ok(Node::Num(*v));
        }
        if FUNCTIONS.iter().map(|f| f.0).chain(BINARY_FUNCTIONS.iter().map(|f| f.0)).any(|f| f == name) {
            return Err(ExpressionError::new(at, format!("{name} is a function: write {name}(…)")));
        }
        let known: Vec<&str> = self.names.variables.iter().copied().chain(constants.map(|c| c.0)).collect();
        Err(ExpressionError::new(at, format!("unknown name \"{name}\"; known names are {}", known.join(", "))))
    }

    /// A call of function `name` (written at `at`), its `(` already read.
    fn call(&mut self, name: &str, at: usize) -> Result<Node, ExpressionError> {
        self.nest()?;
        let first = self.sum()?;
        self.skip_space();
        let comma = self.pos;
        let second = if self.eat(",") { Some((comma, self.sum()?)) } else { None };
        self.close(at + name.len())?;
        self.nesting -= 1;
        let unary = FUNCTIONS.iter().find(|f| f.0 == name).map(|f| f.1);
        let binary_fn = BINARY_FUNCTIONS.iter().find(|f| f.0 == name).map(|f| f.1);
        match (unary, binary_fn, second) {
            (Some(f), _, None) => match first {
                Node::Num(c) => finite(f.apply(c), at),
                n => Ok(Node::Call(f, Box::new(n))),
            },
            (_, Some(b), Some((_, y))) => binary(b, first, y, at),
            (Some(_), _, Some((comma, _))) => {
                Err(ExpressionError::new(comma, format!("{name} takes one argument, given two")))
            }
            (_, Some(_), None) => Err(ExpressionError::new(at, format!("{name} takes two arguments: {name}(a, b)"))),
            (None, None, _) => {
                let all: Vec<&str> =
                    FUNCTIONS.iter().map(|f| f.0).chain(BINARY_FUNCTIONS.iter().map(|f| f.0)).collect();
                Err(ExpressionError::new(at, format!("unknown function \"{name}\"; functions are {}", all.join(", "))))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
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
}
