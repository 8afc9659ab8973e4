//! The parser: text to a tree, by recursive descent over the grammar of [`super`], folding
//! constant sub-expressions as it goes.

use super::functions::{Binary, Function, BINARY_FUNCTIONS, BUILT_IN_CONSTANTS, FUNCTIONS};
use super::{is_name, ExpressionError, Names};

/// The deepest nesting of parentheses, unary signs and function calls accepted: far beyond any
/// metric, and a bound on the parser's recursion over untrusted text.
const MAX_NESTING: usize = 100;

/// The parsed expression, constants already folded.
pub(super) enum Node {
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
pub(super) struct Parser<'a> {
    pub(super) text: &'a str,
    pub(super) names: Names<'a>,
    pub(super) pos: usize,
    pub(super) nesting: usize,
}

impl Parser<'_> {
    pub(super) fn skip_space(&mut self) {
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
    pub(super) fn describe_here(&self) -> String {
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

    pub(super) fn sum(&mut self) -> Result<Node, ExpressionError> {
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
