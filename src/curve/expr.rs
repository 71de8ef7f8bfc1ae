//! A small formula language for parametric curves: numbers, `s`, `pi`, `e`, + − * / ^,
//! parentheses and the usual elementary functions. Formulas are parsed once into a tree and
//! evaluated on jets, so the curve's first and second derivatives are exact.

use super::jet::Jet;

#[derive(Clone, Debug)]
enum Node {
    Num(f64),
    Param,
    Neg(Box<Node>),
    Bin(char, Box<Node>, Box<Node>),
    Call(Func, Box<Node>),
}

#[derive(Clone, Copy, Debug)]
enum Func {
    Sin,
    Cos,
    Tan,
    Exp,
    Ln,
    Sqrt,
    Sinh,
    Cosh,
    Tanh,
    Asin,
    Acos,
    Atan,
    Abs,
}

const FUNCTIONS: [(&str, Func); 14] = [
    ("sin", Func::Sin),
    ("cos", Func::Cos),
    ("tan", Func::Tan),
    ("exp", Func::Exp),
    ("ln", Func::Ln),
    ("log", Func::Ln),
    ("sqrt", Func::Sqrt),
    ("sinh", Func::Sinh),
    ("cosh", Func::Cosh),
    ("tanh", Func::Tanh),
    ("asin", Func::Asin),
    ("acos", Func::Acos),
    ("atan", Func::Atan),
    ("abs", Func::Abs),
];

/// Longest formula accepted. A curve is a few dozen characters; the bound keeps parsing,
/// evaluation (every derivative is a pass over the tree) and dropping the tree shallow and fast.
pub const MAX_CHARS: usize = 1000;
/// Deepest nesting of brackets, signs, powers and calls; each level is a few stack frames of
/// the recursive descent.
pub const MAX_DEPTH: usize = 64;

/// A parsed formula in the curve parameter `s`.
#[derive(Clone, Debug)]
pub struct Formula {
    root: Node,
}

impl Formula {
    pub fn parse(text: &str) -> Result<Formula, String> {
        let length = text.chars().count();
        if length > MAX_CHARS {
            return Err(format!(
                "is {length} characters long; a formula may have at most {MAX_CHARS}"
            ));
        }
        let mut p = Parser {
            chars: text.chars().collect(),
            pos: 0,
            depth: 0,
        };
        let root = p.sum()?;
        p.skip_ws();
        if p.pos < p.chars.len() {
            return Err(format!(
                "unexpected {} at character {}",
                crate::error::quote(&p.chars[p.pos].to_string()),
                p.pos + 1,
            ));
        }
        Ok(Formula { root })
    }

    pub fn eval(&self, s: f64) -> Jet {
        eval(&self.root, Jet::variable(s))
    }
}

fn eval(node: &Node, s: Jet) -> Jet {
    match node {
        Node::Num(v) => Jet::constant(*v),
        Node::Param => s,
        Node::Neg(a) => -eval(a, s),
        Node::Bin(op, a, b) => {
            let (a, b) = (eval(a, s), eval(b, s));
            match op {
                '+' => a + b,
                '-' => a - b,
                '*' => a * b,
                '/' => a / b,
                _ => a.pow(b),
            }
        }
        Node::Call(f, a) => {
            let a = eval(a, s);
            match f {
                Func::Sin => a.sin(),
                Func::Cos => a.cos(),
                Func::Tan => a.tan(),
                Func::Exp => a.exp(),
                Func::Ln => a.ln(),
                Func::Sqrt => a.sqrt(),
                Func::Sinh => a.sinh(),
                Func::Cosh => a.cosh(),
                Func::Tanh => a.tanh(),
                Func::Asin => a.asin(),
                Func::Acos => a.acos(),
                Func::Atan => a.atan(),
                Func::Abs => a.abs(),
            }
        }
    }
}

/// Recursive descent: sum := product (('+'|'-') product)*; product := unary (('*'|'/') unary)*;
/// unary := '-' unary | power; power := atom ('^' unary)?  (right-associative, binds tighter
/// than unary minus on its left, so -s^2 is -(s^2)).
struct Parser {
    chars: Vec<char>,
    pos: usize,
    /// Nesting of `unary`, through which every bracket, sign, power and call passes.
    depth: usize,
}

impl Parser {
    fn skip_ws(&mut self) {
        while self.pos < self.chars.len() && self.chars[self.pos].is_whitespace() {
            self.pos += 1;
        }
    }

    fn peek(&mut self) -> Option<char> {
        self.skip_ws();
        self.chars.get(self.pos).copied()
    }

    fn sum(&mut self) -> Result<Node, String> {
        let mut lhs = self.product()?;
        while let Some(op @ ('+' | '-')) = self.peek() {
            self.pos += 1;
            lhs = Node::Bin(op, Box::new(lhs), Box::new(self.product()?));
        }
        Ok(lhs)
    }

    fn product(&mut self) -> Result<Node, String> {
        let mut lhs = self.unary()?;
        while let Some(op @ ('*' | '/')) = self.peek() {
            self.pos += 1;
            lhs = Node::Bin(op, Box::new(lhs), Box::new(self.unary()?));
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> Result<Node, String> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(format!(
                "nests brackets, signs or powers more than {MAX_DEPTH} deep (at character {})",
                self.pos + 1
            ));
        }
        let node = self.signed();
        self.depth -= 1;
        node
    }

    fn signed(&mut self) -> Result<Node, String> {
        match self.peek() {
            Some('-') => {
                self.pos += 1;
                Ok(Node::Neg(Box::new(self.unary()?)))
            }
            Some('+') => {
                self.pos += 1;
                self.unary()
            }
            _ => self.power(),
        }
    }

    fn power(&mut self) -> Result<Node, String> {
        let base = self.atom()?;
        if self.peek() == Some('^') {
            self.pos += 1;
            return Ok(Node::Bin('^', Box::new(base), Box::new(self.unary()?)));
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Node, String> {
        match self.peek() {
            None => Err("the formula ends where a number, `s` or a function was expected".into()),
            Some('(') => {
                self.pos += 1;
                let inner = self.sum()?;
                self.expect(')')?;
                Ok(inner)
            }
            Some(c) if c.is_ascii_digit() || c == '.' => self.number(),
            Some(c) if c.is_alphabetic() || c == '_' => self.name(),
            Some(c) => Err(format!(
                "unexpected {} at character {}",
                crate::error::quote(&c.to_string()),
                self.pos + 1
            )),
        }
    }

    fn expect(&mut self, c: char) -> Result<(), String> {
        if self.peek() == Some(c) {
            self.pos += 1;
            Ok(())
        } else {
            Err(format!("missing '{c}' at character {}", self.pos + 1))
        }
    }

    fn number(&mut self) -> Result<Node, String> {
        let start = self.pos;
        while self.pos < self.chars.len() {
            let c = self.chars[self.pos];
            let exponent_sign = (c == '-' || c == '+')
                && self.pos > start
                && matches!(self.chars[self.pos - 1], 'e' | 'E');
            if c.is_ascii_digit() || c == '.' || c == 'e' || c == 'E' || exponent_sign {
                self.pos += 1;
            } else {
                break;
            }
        }
        let text: String = self.chars[start..self.pos].iter().collect();
        text.parse::<f64>()
            .map(Node::Num)
            .map_err(|_| format!("{} is not a number", crate::error::quote(&text)))
    }

    fn name(&mut self) -> Result<Node, String> {
        let start = self.pos;
        while self.pos < self.chars.len()
            && (self.chars[self.pos].is_alphanumeric() || self.chars[self.pos] == '_')
        {
            self.pos += 1;
        }
        let name: String = self.chars[start..self.pos].iter().collect();
        match name.as_str() {
            "s" => return Ok(Node::Param),
            "pi" => return Ok(Node::Num(std::f64::consts::PI)),
            "e" => return Ok(Node::Num(std::f64::consts::E)),
            _ => {}
        }
        let Some(&(_, func)) = FUNCTIONS.iter().find(|(n, _)| *n == name) else {
            return Err(if self.peek() == Some('(') {
                format!(
                    "unknown function {} (known: {})",
                    crate::error::quote(&name),
                    FUNCTIONS.map(|(n, _)| n).join(", ")
                )
            } else {
                format!(
                    "unknown name {} (the parameter is `s`; constants are `pi` and `e`)",
                    crate::error::quote(&name)
                )
            });
        };
        self.expect('(')?;
        let arg = self.sum()?;
        self.expect(')')?;
        Ok(Node::Call(func, Box::new(arg)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn precedence_and_derivatives() {
        let f = Formula::parse("-s^2 + 2*sin(s)/ (1 + 1e-1*s)").unwrap();
        let x = 0.3_f64;
        let j = f.eval(x);
        let expect = -x * x + 2.0 * x.sin() / (1.0 + 0.1 * x);
        assert!((j.v - expect).abs() < 1e-15);
        let g = Formula::parse("2^3^2").unwrap().eval(0.0);
        assert_eq!(g.v, 512.0);
    }

    #[test]
    fn errors_name_the_problem() {
        assert!(Formula::parse("foo(s)")
            .unwrap_err()
            .contains("unknown function 'foo'"));
        assert!(Formula::parse("s +").is_err());
        assert!(Formula::parse("(s").unwrap_err().contains("missing ')'"));
        assert!(Formula::parse("x")
            .unwrap_err()
            .contains("unknown name 'x'"));
    }

    /// Hostile formulas end in a sentence, not a stack overflow: nesting past the bound, and
    /// text past the length bound, are refused; the deepest accepted nesting parses.
    #[test]
    fn nesting_and_length_are_bounded() {
        let nested = |n: usize| format!("{}s{}", "(".repeat(n), ")".repeat(n));
        assert!(Formula::parse(&nested(MAX_DEPTH - 1)).is_ok());
        assert!(Formula::parse(&nested(MAX_DEPTH + 1))
            .unwrap_err()
            .contains("more than 64 deep"));
        assert!(Formula::parse(&format!("{}s", "-".repeat(500)))
            .unwrap_err()
            .contains("deep"));
        assert!(Formula::parse(&format!("s{}", "^s".repeat(400)))
            .unwrap_err()
            .contains("deep"));
        let long = format!("0{}", "+s".repeat(MAX_CHARS));
        assert!(Formula::parse(&long).unwrap_err().contains("at most 1000"));
        let widest = format!("0{}", "+s".repeat((MAX_CHARS - 1) / 2));
        assert_eq!(Formula::parse(&widest).unwrap().eval(1.0).v, 499.0);
    }
}
