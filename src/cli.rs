//! Value parsers shared by the command-line subcommands (clap's
//! `value_parser`): one rule and one message for each kind of argument.

/// Parses `WIDTHxHEIGHT` (or `WIDTHXHEIGHT`), each from 1 to 16384.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, got {text:?}"))?;
    let parse = |s: &str| {
        s.trim()
            .parse::<u32>()
            .ok()
            .filter(|n| (1..=16384).contains(n))
            .ok_or_else(|| format!("expected a size from 1 to 16384, got {s:?}"))
    };
    Ok((parse(w)?, parse(h)?))
}

#[cfg(test)]
mod tests {
    use super::parse_size;

    #[test]
    fn sizes_parse_and_bad_ones_are_named() {
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert_eq!(parse_size("16384X1"), Ok((16384, 1)));
        assert_eq!(
            parse_size("640"),
            Err("expected WIDTHxHEIGHT, got \"640\"".to_string())
        );
        assert_eq!(
            parse_size("0x480"),
            Err("expected a size from 1 to 16384, got \"0\"".to_string())
        );
        assert!(parse_size("16385x1").is_err());
    }
}
