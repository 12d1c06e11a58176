//! What the targets are fed: the random bytes each input is drawn from
//! (the same for a seed and an index on every run, so a failing input can
//! be made again from its number), and the mutations and number choices
//! the structure-aware generators share.

use arbitrary::{Result, Unstructured};

/// Random bytes per input: what [`Unstructured`] draws every choice from.
/// Past the end its choices fall back to the smallest; 4 KiB is more than
/// any generator here asks for.
const BYTES_PER_INPUT: usize = 4096;

/// The bytes of input `index` of `target` under `seed` (splitmix64, whose
/// state is a plain counter, so input `index` needs no input before it).
pub fn random_bytes(target: &str, seed: u64, index: u64) -> Vec<u8> {
    let name = target.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
    });
    let mut state = seed ^ name ^ index.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    let mut bytes = Vec::with_capacity(BYTES_PER_INPUT);
    while bytes.len() < BYTES_PER_INPUT {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        bytes.extend_from_slice(&(z ^ (z >> 31)).to_le_bytes());
    }
    bytes
}

/// Numbers at the edges: of f32 and f64, of the integers the formats
/// store, and spellings some parsers take and others refuse.
const EXTREME_NUMBERS: [&str; 36] = [
    "0",
    "-0",
    "-0.0",
    "1",
    "-1",
    "1e-30",
    "1e30",
    "-1e30",
    "1e-45",
    "1.4e-45",
    "3.4028235e38",
    "3.5e38",
    "1e38",
    "1e39",
    "1e-38",
    "1e300",
    "1e308",
    "1.7976931348623157e308",
    "1e309",
    "-1e309",
    "5e-324",
    "1e-400",
    "inf",
    "-inf",
    "nan",
    "+nan",
    "2147483647",
    "2147483648",
    "-2147483649",
    "4294967295",
    "4294967296",
    "9223372036854775807",
    "18446744073709551616",
    "0x10",
    "1_000",
    "00000000000000000000000000000000000001",
];

/// A number as a user could write it: mostly an edge, else any f64 in
/// plain or exponent form, or a small integer.
pub fn number(u: &mut Unstructured) -> Result<String> {
    Ok(match u.int_in_range(0..=3)? {
        0 | 1 => u.choose(&EXTREME_NUMBERS)?.to_string(),
        2 => {
            let x: f64 = u.arbitrary()?;
            if u.arbitrary()? {
                format!("{x:e}")
            } else {
                format!("{x}")
            }
        }
        _ => u.int_in_range(-4i32..=20)?.to_string(),
    })
}

/// `[a, b, c]` of [`number`]s, sometimes of the wrong length.
pub fn vector(u: &mut Unstructured) -> Result<String> {
    let len = if u.ratio(1, 8)? {
        u.int_in_range(0..=5)?
    } else {
        3
    };
    let parts: Vec<String> = (0..len).map(|_| number(u)).collect::<Result<_>>()?;
    Ok(format!("[{}]", parts.join(", ")))
}

/// Characters that break text in interesting ways: line ends of every
/// system, NUL, a byte-order mark, multi-byte letters, quotes, escapes.
const ODD_CHARACTERS: [char; 16] = [
    '\n',
    '\r',
    '\t',
    '\0',
    '\u{feff}',
    'é',
    '\u{1F600}',
    '\u{202e}',
    '"',
    '\'',
    '\\',
    '#',
    '=',
    '[',
    ']',
    '\u{7f}',
];

/// The most characters one mutation repeating a line adds.
const MAX_ADDED: usize = 64 << 10;

/// 1 to 4 mutations of `text`: deletions, insertions of `tokens` (what
/// the format's mistakes are made of), numbers at the edges, repeated,
/// swapped and deleted lines, odd characters, deep nesting and a cut end.
pub fn mutate(u: &mut Unstructured, text: &str, tokens: &[&str]) -> Result<String> {
    let mut chars: Vec<char> = text.chars().collect();
    for _ in 0..u.int_in_range(1..=4)? {
        let at = u.int_in_range(0..=chars.len())?;
        match u.int_in_range(0..=9)? {
            0 => {
                let end = (at + u.int_in_range(1..=20)?).min(chars.len());
                chars.drain(at..end);
            }
            1 | 2 => {
                let token = u.choose(tokens)?;
                chars.splice(at..at, token.chars());
            }
            3 | 4 => replace_number(u, &mut chars)?,
            5 => {
                let line = line_around(&chars, at);
                // Many copies of short lines; inputs stay under a megabyte.
                let most = (MAX_ADDED / line.len().max(1)).clamp(1, 200);
                let copies = if u.ratio(1, 4)? {
                    u.int_in_range(1..=most)?
                } else {
                    1
                };
                let copy: Vec<char> = chars[line.clone()].to_vec();
                for _ in 0..copies {
                    chars.splice(line.end..line.end, copy.iter().copied());
                }
            }
            6 => {
                let line = line_around(&chars, at);
                chars.drain(line);
            }
            7 => {
                let c = *u.choose(&ODD_CHARACTERS)?;
                chars.insert(at, c);
            }
            8 => {
                let depth = u.int_in_range(1..=3000)?;
                let (open, close) = *u.choose(&[("(", ")"), ("[", "]"), ("{", "}"), ("-", "")])?;
                let end = (at + u.int_in_range(0..=10)?).min(chars.len());
                chars.splice(end..end, close.repeat(depth).chars());
                chars.splice(at..at, open.repeat(depth).chars());
            }
            _ => chars.truncate(at),
        }
    }
    Ok(chars.into_iter().collect())
}

/// Replaces the number (a run of digits, signs, dots and exponents) at a
/// random place of `chars` with [`number`]; inserts one if there is none.
fn replace_number(u: &mut Unstructured, chars: &mut Vec<char>) -> Result<()> {
    let starts: Vec<usize> = (0..chars.len())
        .filter(|&i| chars[i].is_ascii_digit() && (i == 0 || !chars[i - 1].is_ascii_digit()))
        .collect();
    let replacement: Vec<char> = number(u)?.chars().collect();
    if starts.is_empty() {
        let at = u.int_in_range(0..=chars.len())?;
        chars.splice(at..at, replacement);
        return Ok(());
    }
    let start = *u.choose(&starts)?;
    let numeric = |c: char| c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '-' | '+');
    let end = (start..chars.len())
        .find(|&i| !numeric(chars[i]))
        .unwrap_or(chars.len());
    chars.splice(start..end, replacement);
    Ok(())
}

/// The line (with its `\n`) that holds `at`.
fn line_around(chars: &[char], at: usize) -> std::ops::Range<usize> {
    let start = chars[..at]
        .iter()
        .rposition(|&c| c == '\n')
        .map_or(0, |i| i + 1);
    let end = chars[at..]
        .iter()
        .position(|&c| c == '\n')
        .map_or(chars.len(), |i| at + i + 1);
    start..end
}

/// 1 to 8 byte-level mutations, for binary formats: flipped bits, bytes
/// at the edges of their types, deleted, repeated and random runs, a cut.
pub fn mutate_bytes(u: &mut Unstructured, bytes: &[u8]) -> Result<Vec<u8>> {
    let mut bytes = bytes.to_vec();
    for _ in 0..u.int_in_range(1..=8)? {
        let at = u.int_in_range(0..=bytes.len())?;
        match u.int_in_range(0..=5)? {
            0 if at < bytes.len() => bytes[at] ^= 1 << u.int_in_range(0..=7)?,
            1 if at < bytes.len() => bytes[at] = *u.choose(&[0u8, 1, 0x7f, 0x80, 0xff])?,
            2 => {
                let end = (at + u.int_in_range(1..=64)?).min(bytes.len());
                bytes.drain(at..end);
            }
            3 => {
                let end = (at + u.int_in_range(1..=16)?).min(bytes.len());
                let copy = bytes[at..end].to_vec();
                for _ in 0..u.int_in_range(1..=32)? {
                    bytes.splice(at..at, copy.iter().copied());
                }
            }
            4 => {
                let random: Vec<u8> = (0..u.int_in_range(1..=16)?)
                    .map(|_| u.arbitrary())
                    .collect::<Result<_>>()?;
                bytes.splice(at..at, random);
            }
            _ => bytes.truncate(at),
        }
    }
    Ok(bytes)
}

/// Up to `max` random characters, mostly printable ASCII.
pub fn random_text(u: &mut Unstructured, max: usize) -> Result<String> {
    let len = u.int_in_range(0..=max)?;
    (0..len)
        .map(|_| {
            Ok(if u.ratio(1, 10)? {
                *u.choose(&ODD_CHARACTERS)?
            } else {
                char::from(u.int_in_range(0x20u8..=0x7e)?)
            })
        })
        .collect()
}
