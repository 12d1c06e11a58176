//! A small lexer shared by the WGSL and GLSL paths: tokens with their byte
//! offsets, comments kept aside (parameter annotations live in them), and
//! preprocessor lines as single tokens. It only needs to be good enough to
//! find declarations at the top level; naga does the real parsing.

/// What a token is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Ident,
    Number,
    /// One punctuation character (`{`, `;`, `(`, ...); `@` too.
    Punct,
    /// A whole preprocessor line (`#version 450`), from `#` to the end of
    /// the line (continuation lines included).
    Directive,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Token<'a> {
    pub kind: Kind,
    pub text: &'a str,
    /// Byte offset in the scanned text.
    pub start: usize,
}

impl Token<'_> {
    pub fn end(&self) -> usize {
        self.start + self.text.len()
    }

    pub fn is(&self, text: &str) -> bool {
        self.text == text
    }
}

/// The deepest nesting a shader may have: brackets of any kind, plus a run
/// of prefix operators (`-`, `+`, `!`, `~`). naga's GLSL front end parses
/// each level by a recursive call and ran out of a 2 MiB stack at 1,600
/// levels (docs/reliability.md, "Fuzzing"); real shaders nest a few dozen.
pub const MAX_NESTING: usize = 200;

/// How deep the tokens read so far nest: open brackets, and the prefix
/// operators in a row just read.
#[derive(Default)]
struct Nesting {
    brackets: usize,
    operators: usize,
}

impl Nesting {
    /// Reads the next token; true when it nests deeper than [`MAX_NESTING`].
    fn step(&mut self, token: &str) -> bool {
        match token {
            "(" | "[" | "{" => self.brackets += 1,
            ")" | "]" | "}" => self.brackets = self.brackets.saturating_sub(1),
            _ => {}
        }
        let prefix = matches!(token, "-" | "+" | "!" | "~");
        self.operators = if prefix { self.operators + 1 } else { 0 };
        self.brackets + self.operators > MAX_NESTING
    }
}

/// A `//` or `/* */` comment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Comment<'a> {
    /// The text without the comment markers.
    pub body: &'a str,
    /// Byte offsets of the body in the scanned text.
    pub body_start: usize,
    /// 1-based line of the comment's first character.
    pub line: u32,
    /// Nothing but white space precedes it on its line.
    pub own_line: bool,
}

/// The indices of the tokens at brace depth 0 (outside every `{ }`, a
/// closing brace back at 0 included): where a shader's top-level
/// declarations start. A closing brace with no opening one (a body opened
/// by a macro: `#define Main void mainImage(...) {`, then `Main ... }`)
/// leaves the depth at 0, so what follows is still top level.
pub fn top_level(tokens: &[Token]) -> impl Iterator<Item = usize> {
    tokens
        .iter()
        .enumerate()
        .scan(0u32, |depth, (i, t)| {
            match t.text {
                "{" => *depth += 1,
                "}" => *depth = depth.saturating_sub(1),
                _ => {}
            }
            Some((*depth == 0).then_some(i))
        })
        .flatten()
}

/// The scanned text.
#[derive(Debug)]
pub struct Scan<'a> {
    pub text: &'a str,
    pub tokens: Vec<Token<'a>>,
    pub comments: Vec<Comment<'a>>,
    /// Byte offset of the start of each line.
    line_starts: Vec<usize>,
}

impl<'a> Scan<'a> {
    pub fn new(text: &'a str) -> Self {
        let bytes = text.as_bytes();
        let line_starts: Vec<usize> = std::iter::once(0)
            .chain(
                bytes
                    .iter()
                    .enumerate()
                    .filter(|(_, b)| **b == b'\n')
                    .map(|(i, _)| i + 1),
            )
            .collect();
        let mut scan = Scan {
            text,
            tokens: Vec::new(),
            comments: Vec::new(),
            line_starts,
        };
        let mut i = 0;
        while i < bytes.len() {
            let c = bytes[i];
            if c.is_ascii_whitespace() {
                i += 1;
            } else if bytes[i..].starts_with(b"//") {
                let end = text[i..].find('\n').map_or(text.len(), |n| i + n);
                scan.push_comment(i, i + 2, end);
                i = end;
            } else if bytes[i..].starts_with(b"/*") {
                let end = text[i + 2..].find("*/").map_or(text.len(), |n| i + 2 + n);
                scan.push_comment(i, i + 2, end);
                i = (end + 2).min(text.len());
            } else if c == b'#' && scan.at_line_start(i) {
                let mut end = i;
                loop {
                    end = text[end..].find('\n').map_or(text.len(), |n| end + n);
                    // A backslash before the newline continues the directive.
                    if end < text.len() && text[..end].trim_end_matches('\r').ends_with('\\') {
                        end += 1;
                        continue;
                    }
                    break;
                }
                scan.push(Kind::Directive, i, end);
                i = end;
            } else if c.is_ascii_alphabetic() || c == b'_' {
                let end = i + text[i..]
                    .find(|ch: char| !(ch.is_ascii_alphanumeric() || ch == '_'))
                    .unwrap_or(text.len() - i);
                scan.push(Kind::Ident, i, end);
                i = end;
            } else if c.is_ascii_digit()
                || (c == b'.' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit))
            {
                let mut end = i + 1;
                while end < bytes.len() {
                    let b = bytes[end];
                    let exponent_sign = (b == b'-' || b == b'+')
                        && matches!(bytes[end - 1], b'e' | b'E')
                        && !text[i..end].starts_with("0x");
                    if b.is_ascii_alphanumeric() || b == b'.' || b == b'_' || exponent_sign {
                        end += 1;
                    } else {
                        break;
                    }
                }
                scan.push(Kind::Number, i, end);
                i = end;
            } else {
                let len = text[i..].chars().next().map_or(1, char::len_utf8);
                scan.push(Kind::Punct, i, i + len);
                i += len;
            }
        }
        scan
    }

    /// Drops the tokens of preprocessor branches that are not taken, so
    /// that `#ifdef A void main() { #else void mainImage(...) { #endif`
    /// reads as one function. `defined` are the macros defined before the
    /// text (as `1`); `#define`s in taken branches add to them, with their
    /// values. `#if`/`#elif` conditions are evaluated when they are simple
    /// (see [`condition`]); others count as true: then the first branch is
    /// read. The directives themselves stay.
    pub fn drop_inactive_branches(&mut self, defined: &[&str]) {
        let mut defined: Vec<(String, String)> = defined
            .iter()
            .map(|d| (d.to_string(), "1".to_string()))
            .collect();
        // Per open `#if`: (this branch is taken, a branch of it was taken).
        let mut open: Vec<(bool, bool)> = Vec::new();
        let mut kept = Vec::with_capacity(self.tokens.len());
        for token in std::mem::take(&mut self.tokens) {
            let active = open.iter().all(|(taken, _)| *taken);
            if token.kind != Kind::Directive {
                if active {
                    kept.push(token);
                }
                continue;
            }
            let body = token.text[1..].split("//").next().unwrap_or_default();
            let mut words = body.split_whitespace();
            let keyword = words.next().unwrap_or_default();
            let rest: String = words.collect::<Vec<_>>().join(" ");
            let first_word = rest.split_whitespace().next().unwrap_or_default();
            match keyword {
                "ifdef" => {
                    let taken = defined.iter().any(|(d, _)| d == first_word);
                    open.push((taken, taken));
                }
                "ifndef" => {
                    let taken = !defined.iter().any(|(d, _)| d == first_word);
                    open.push((taken, taken));
                }
                "if" => {
                    let taken = condition(&rest, &defined);
                    open.push((taken, taken));
                }
                "elif" => {
                    if let Some((taken, any)) = open.last_mut() {
                        *taken = !*any && condition(&rest, &defined);
                        *any |= *taken;
                    }
                }
                "else" => {
                    if let Some((taken, any)) = open.last_mut() {
                        *taken = !*any;
                        *any = true;
                    }
                }
                "endif" => {
                    open.pop();
                }
                "define" if active => {
                    let name = first_word.split('(').next().unwrap_or_default();
                    let value = rest[first_word.len()..].trim();
                    defined.push((name.to_string(), value.to_string()));
                }
                "undef" if active => defined.retain(|(d, _)| d != first_word),
                _ => {}
            }
            kept.push(token);
        }
        self.tokens = kept;
    }

    fn at_line_start(&self, offset: usize) -> bool {
        let start = self.line_starts[self.line_index(offset)];
        self.text[start..offset].trim().is_empty()
    }

    fn push(&mut self, kind: Kind, start: usize, end: usize) {
        self.tokens.push(Token {
            kind,
            text: &self.text[start..end],
            start,
        });
    }

    fn push_comment(&mut self, start: usize, body_start: usize, body_end: usize) {
        let own_line = self.at_line_start(start);
        self.comments.push(Comment {
            body: &self.text[body_start..body_end],
            body_start,
            line: self.line_of(start),
            own_line,
        });
    }

    fn line_index(&self, offset: usize) -> usize {
        self.line_starts.partition_point(|&s| s <= offset) - 1
    }

    /// 1-based line of a byte offset.
    pub fn line_of(&self, offset: usize) -> u32 {
        self.line_index(offset) as u32 + 1
    }

    /// 1-based column (in bytes, as naga counts) of a byte offset.
    pub fn column_of(&self, offset: usize) -> u32 {
        (offset - self.line_starts[self.line_index(offset)]) as u32 + 1
    }

    /// The byte offset of a 1-based line and column, if it is in the text.
    pub fn offset_of(&self, line: u32, column: u32) -> Option<usize> {
        let start = *self.line_starts.get(line.checked_sub(1)? as usize)?;
        let offset = start + column.checked_sub(1)? as usize;
        (offset <= self.text.len()).then_some(offset)
    }

    /// The text of a 1-based line, without its newline.
    pub fn line_text(&self, line: u32) -> &'a str {
        let Some(&start) = self.line_starts.get(line.saturating_sub(1) as usize) else {
            return "";
        };
        let end = self.text[start..]
            .find('\n')
            .map_or(self.text.len(), |n| start + n);
        self.text[start..end].trim_end_matches('\r')
    }

    /// The comments that annotate a declaration on `line`: a comment on the
    /// same line, else the comment-only lines right above it.
    pub fn comments_for_line(&self, line: u32) -> Vec<Comment<'a>> {
        let same: Vec<Comment> = self
            .comments
            .iter()
            .filter(|c| c.line == line && !c.own_line)
            .copied()
            .collect();
        if !same.is_empty() {
            return same;
        }
        let mut above = Vec::new();
        let mut want = line.saturating_sub(1);
        for c in self.comments.iter().rev() {
            if c.line > want {
                continue;
            }
            if c.line == want && c.own_line && !self.has_token_on_line(want) {
                above.push(*c);
                want = want.saturating_sub(1);
            } else {
                break;
            }
        }
        above.reverse();
        above
    }

    /// The offset of the first token nested deeper than [`MAX_NESTING`].
    /// A directive's own expression (`#if ((...))`) counts on its own: the
    /// preprocessor parses it recursively too.
    pub fn too_deep(&self) -> Option<usize> {
        let mut nesting = Nesting::default();
        for token in &self.tokens {
            let deep = if token.kind == Kind::Directive {
                let mut own = Nesting::default();
                let mut buffer = [0; 4];
                token
                    .text
                    .chars()
                    .filter(|c| !c.is_whitespace())
                    .any(|c| own.step(c.encode_utf8(&mut buffer)))
            } else {
                nesting.step(token.text)
            };
            if deep {
                return Some(token.start);
            }
        }
        None
    }

    fn has_token_on_line(&self, line: u32) -> bool {
        self.tokens.iter().any(|t| self.line_of(t.start) == line)
    }
}

/// The value of a preprocessor condition as far as it can be told without
/// a full preprocessor: `||` and `&&` of terms, each `[!]defined(NAME)`,
/// `[!]defined NAME`, a number or macro (true when not zero), or a
/// comparison (`==`, `!=`, `<`, `<=`, `>`, `>=`) of two of them, as in
/// `#if SHADERTOY == 1`. A macro not defined is 0, as in C. Anything else
/// counts as true.
fn condition(expression: &str, defined: &[(String, String)]) -> bool {
    let compact: String = expression.chars().filter(|c| !c.is_whitespace()).collect();
    let compact = compact
        .replace("defined(", "defined ")
        .replace("defined", "defined ");
    evaluate(&compact, defined).unwrap_or(true)
}

/// `None` when the expression is not simple enough for [`condition`].
fn evaluate(expression: &str, defined: &[(String, String)]) -> Option<bool> {
    if expression.contains("||") {
        let mut any = false;
        for term in expression.split("||") {
            any |= evaluate(term, defined)?;
        }
        return Some(any);
    }
    if expression.contains("&&") {
        let mut all = true;
        for term in expression.split("&&") {
            all &= evaluate(term, defined)?;
        }
        return Some(all);
    }
    let term = expression.trim();
    if let Some(inner) = term.strip_prefix('(').and_then(|t| t.strip_suffix(')')) {
        return evaluate(inner, defined);
    }
    if let Some(name) = term.strip_prefix("defined ") {
        let name = name.trim().trim_start_matches('(').trim_end_matches(')');
        return Some(defined.iter().any(|(d, _)| d == name));
    }
    for op in ["==", "!=", "<=", ">=", "<", ">"] {
        if let Some((left, right)) = term.split_once(op) {
            let (a, b) = (value(left, defined)?, value(right, defined)?);
            return Some(match op {
                "==" => a == b,
                "!=" => a != b,
                "<=" => a <= b,
                ">=" => a >= b,
                "<" => a < b,
                _ => a > b,
            });
        }
    }
    if let Some(rest) = term.strip_prefix('!') {
        return evaluate(rest, defined).map(|v| !v);
    }
    value(term, defined).map(|v| v != 0)
}

/// An integer or the integer a macro is defined as (0 when not defined).
fn value(operand: &str, defined: &[(String, String)]) -> Option<i64> {
    let operand = operand.trim().trim_start_matches('(').trim_end_matches(')');
    if let Ok(number) = operand
        .trim_end_matches(['u', 'U', 'l', 'L'])
        .parse::<i64>()
    {
        return Some(number);
    }
    if !operand
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '_')
        || operand.is_empty()
    {
        return None;
    }
    match defined.iter().rev().find(|(d, _)| d == operand) {
        Some((_, body)) if body.is_empty() => None,
        Some((_, body)) => body.trim().parse::<i64>().ok(),
        None => Some(0),
    }
}

/// Replaces `text[range]` with spaces, keeping newlines, so that every byte
/// offset (and so every line and column) of the rest of the text is unchanged.
pub fn blank(text: &mut String, range: std::ops::Range<usize>) {
    let blanked: String = text[range.clone()]
        .chars()
        .map(|c| {
            if c == '\n' || c == '\r' {
                c.to_string()
            } else {
                " ".repeat(c.len_utf8())
            }
        })
        .collect();
    text.replace_range(range, &blanked);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tokens of `scan` that are code, not directives.
    fn code_tokens<'a>(scan: &Scan<'a>) -> Vec<&'a str> {
        scan.tokens
            .iter()
            .filter(|t| t.kind != Kind::Directive)
            .map(|t| t.text)
            .collect()
    }

    #[test]
    fn a_body_opened_by_a_macro_leaves_the_rest_top_level() {
        let text = "#define Main void f() {\nMain x = 1.0; }\nvoid main() { y(); }\n";
        let scan = Scan::new(text);
        let top: Vec<&str> = top_level(&scan.tokens)
            .map(|i| scan.tokens[i].text)
            .filter(|t| !t.starts_with('#'))
            .collect();
        assert_eq!(
            top,
            [
                "Main", "x", "=", "1.0", ";", "}", "void", "main", "(", ")", "}"
            ]
        );
    }

    #[test]
    fn tokens_comments_and_directives() {
        let text =
            "#version 300 es\nuniform float t; // @slider(0, 1e-3)\n/* a\n b */ x = .5e+2;\n";
        let scan = Scan::new(text);
        let kinds: Vec<(Kind, &str)> = scan.tokens.iter().map(|t| (t.kind, t.text)).collect();
        assert_eq!(
            kinds,
            [
                (Kind::Directive, "#version 300 es"),
                (Kind::Ident, "uniform"),
                (Kind::Ident, "float"),
                (Kind::Ident, "t"),
                (Kind::Punct, ";"),
                (Kind::Ident, "x"),
                (Kind::Punct, "="),
                (Kind::Number, ".5e+2"),
                (Kind::Punct, ";"),
            ]
        );
        assert_eq!(scan.comments.len(), 2);
        assert_eq!(scan.comments[0].body, " @slider(0, 1e-3)");
        assert_eq!(scan.comments[0].line, 2);
        assert!(!scan.comments[0].own_line);
        assert!(scan.comments[1].own_line);
        assert_eq!(scan.line_of(scan.tokens[5].start), 4);
        assert_eq!(scan.line_text(2), "uniform float t; // @slider(0, 1e-3)");
    }

    #[test]
    fn comments_above_a_declaration_belong_to_it() {
        let text = "// unrelated\n\n// @color\n// the tint\nvec3 tint;\nfloat a; // @checkbox\n";
        let scan = Scan::new(text);
        let above: Vec<&str> = scan.comments_for_line(5).iter().map(|c| c.body).collect();
        assert_eq!(above, [" @color", " the tint"]);
        let same: Vec<&str> = scan.comments_for_line(6).iter().map(|c| c.body).collect();
        assert_eq!(same, [" @checkbox"]);
    }

    #[test]
    fn untaken_preprocessor_branches_are_dropped() {
        let text = "\
#ifdef GL_ES
precision mediump float;
#else
#error no
#endif
#define SHADERTOY
#ifndef SHADERTOY
void main() {
#elif defined(SHADERTOY) // the one taken
void mainImage(out vec4 c, in vec2 p) {
#else
void other() {
#endif
    c = vec4(1.0);
}
#if 0
}
#endif
";
        let mut scan = Scan::new(text);
        scan.drop_inactive_branches(&["GL_ES"]);
        let code = code_tokens(&scan);
        let joined = code.join(" ");
        assert!(
            joined.starts_with("precision mediump float ; void mainImage"),
            "{joined}"
        );
        assert!(!joined.contains("main ("), "{joined}");
        assert!(!joined.contains("other"), "{joined}");
        assert_eq!(code.iter().filter(|t| **t == "}").count(), 1, "{joined}");
        // The directives stay, taken or not (11 of them).
        assert_eq!(
            scan.tokens
                .iter()
                .filter(|t| t.kind == Kind::Directive)
                .count(),
            11
        );
    }

    #[test]
    fn simple_if_conditions_are_evaluated() {
        let text = "\
#define SHADERTOY 1
#define VERSION 2
#if SHADERTOY == 1
void mainImage(out vec4 c, in vec2 p) {
#else
void main() {
#endif
}
#if VERSION > 2 || !defined(SHADERTOY)
int newer;
#elif VERSION != 2
int other;
#elif defined(SHADERTOY) && VERSION >= 2
int taken;
#endif
#if UNDEFINED == 1
int not_this;
#endif
";
        let mut scan = Scan::new(text);
        scan.drop_inactive_branches(&["GL_ES"]);
        let code = code_tokens(&scan);
        let joined = code.join(" ");
        assert_eq!(
            joined,
            "void mainImage ( out vec4 c , in vec2 p ) { } int taken ;"
        );
        let defined = [("A".to_string(), "3".to_string())];
        assert!(condition("A == 3", &defined));
        assert!(!condition("(A < 3)", &defined));
        assert!(!condition("B", &defined), "an undefined macro is 0");
        // Beyond this reading (arithmetic): the first branch, as before.
        assert!(condition("A + 1 == 4", &defined));
    }

    #[test]
    fn blanking_keeps_offsets() {
        let mut text = "a\nuniform float é;\nb".to_string();
        let len = text.len();
        let end = text.find('b').unwrap();
        blank(&mut text, 2..end);
        assert_eq!(text.len(), len);
        assert_eq!(text.lines().nth(2), Some("b"));
    }
}
