//! Numbers as record files write them: free format with values that may lack a leading zero
//! (`.1181069E-02`) or touch their neighbour (`-0.123-0.456`), and Fortran fixed-width fields
//! (`Format=(8F10.5)`).

/// Splits a line of free-format numbers. A sign that does not follow an exponent letter starts
/// a new number, so values written without spaces between them are still read.
pub fn free_format(line: &str) -> Result<Vec<f64>, String> {
    let mut out = Vec::new();
    free_format_into(line, &mut out)?;
    Ok(out)
}

/// [`free_format`] appending to `out`: a reader of thousands of lines fills one vector.
pub fn free_format_into(line: &str, out: &mut Vec<f64>) -> Result<(), String> {
    // Numbers are read where they lie in the line; every byte that ends or starts one is
    // ASCII, so each is a slice of whole characters.
    let bytes = line.as_bytes();
    let mut start = None;
    for (i, &c) in bytes.iter().enumerate() {
        match c {
            b' ' | b'\t' | b',' | b';' => {
                if let Some(s) = start.take() {
                    out.push(number(&line[s..i])?);
                }
            }
            b'+' | b'-' => match start {
                Some(s) if !matches!(bytes[i - 1], b'e' | b'E' | b'd' | b'D') => {
                    out.push(number(&line[s..i])?);
                    start = Some(i);
                }
                Some(_) => {}
                None => start = Some(i),
            },
            _ => {
                start.get_or_insert(i);
            }
        }
    }
    if let Some(s) = start {
        out.push(number(&line[s..])?);
    }
    Ok(())
}

/// One free-format number, a Fortran double's exponent letter `d` read as `e`.
fn number(text: &str) -> Result<f64, String> {
    let spelled;
    let text = if text.bytes().any(|b| matches!(b, b'd' | b'D')) {
        spelled = text.replace(['d', 'D'], "e");
        spelled.as_str()
    } else {
        text
    };
    let v: f64 = text
        .parse()
        .map_err(|_| format!("\"{text}\" is not a number"))?;
    if !v.is_finite() {
        return Err(format!("\"{text}\" is not a finite number"));
    }
    Ok(v)
}

/// A Fortran edit descriptor such as `(8F10.5)`, `(10I8)`, `(1P5E15.7)`: values per line and
/// field width.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FixedFormat {
    /// Values per line.
    pub per_line: usize,
    /// Characters per value.
    pub width: usize,
}

impl FixedFormat {
    /// Parses the descriptor (the text inside or including the parentheses).
    pub fn parse(spec: &str) -> Option<FixedFormat> {
        let s = spec
            .trim()
            .trim_start_matches('(')
            .trim_end_matches(')')
            .trim()
            .to_ascii_uppercase();
        // Drop a scale factor such as 1P.
        let s = match s.find('P') {
            Some(i) if s[..i].chars().all(|c| c.is_ascii_digit()) => s[i + 1..].to_string(),
            _ => s,
        };
        let letter = s.find(|c: char| c.is_ascii_alphabetic())?;
        let per_line = if letter == 0 {
            1
        } else {
            s[..letter].parse().ok()?
        };
        let rest = &s[letter + 1..];
        let width: usize = rest.split('.').next()?.parse().ok()?;
        (per_line > 0 && width > 0).then_some(FixedFormat { per_line, width })
    }

    /// Reads the values of one line field by field (a short last line holds fewer).
    pub fn values(&self, line: &str) -> Result<Vec<f64>, String> {
        let chars: Vec<char> = line.trim_end().chars().collect();
        let mut out = Vec::new();
        for k in 0..self.per_line {
            let (a, b) = (k * self.width, ((k + 1) * self.width).min(chars.len()));
            if a >= chars.len() {
                break;
            }
            let field: String = chars[a..b].iter().collect();
            let field = field.trim();
            if field.is_empty() {
                continue;
            }
            let v: f64 = field
                .replace(['d', 'D'], "e")
                .parse()
                .map_err(|_| format!("field {} \"{field}\" is not a number", k + 1))?;
            if !v.is_finite() {
                return Err(format!(
                    "field {} \"{field}\" is not a finite number",
                    k + 1
                ));
            }
            out.push(v);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_format_reads_touching_values_and_missing_zeros() {
        assert_eq!(
            free_format("  -.6403182E-02   .5304162E-03").unwrap(),
            vec![-0.006403182, 0.0005304162]
        );
        assert_eq!(
            free_format("-0.123-0.456 1.5E+02-2").unwrap(),
            vec![-0.123, -0.456, 150.0, -2.0]
        );
        assert_eq!(free_format("1.0D-3").unwrap(), vec![0.001]);
        assert!(free_format("1.2.3").is_err());
        assert!(free_format("NaN").is_err());
    }

    #[test]
    fn free_format_appends_each_line_to_the_values_read_before() {
        let mut values = vec![1.0];
        free_format_into(" 2.5D+01,-3-4 ", &mut values).unwrap();
        free_format_into("", &mut values).unwrap();
        free_format_into(".5e-1;6", &mut values).unwrap();
        assert_eq!(values, vec![1.0, 25.0, -3.0, -4.0, 0.05, 6.0]);
        assert_eq!(
            free_format_into("7 8x 9", &mut values),
            Err("\"8x\" is not a number".to_string())
        );
        assert_eq!(
            free_format("1d999"),
            Err("\"1e999\" is not a finite number".to_string())
        );
    }

    #[test]
    fn fixed_width_fields() {
        let f = FixedFormat::parse("(8F10.5)").unwrap();
        assert_eq!(
            f,
            FixedFormat {
                per_line: 8,
                width: 10
            }
        );
        assert_eq!(
            f.values("   0.00630-100.12345   0.00099").unwrap(),
            vec![0.0063, -100.12345, 0.00099]
        );
        assert_eq!(
            FixedFormat::parse("(1P5E15.7)").unwrap(),
            FixedFormat {
                per_line: 5,
                width: 15
            }
        );
        assert_eq!(
            FixedFormat::parse("(10I8)").unwrap(),
            FixedFormat {
                per_line: 10,
                width: 8
            }
        );
        assert!(f.values("   0.0x630").is_err());
    }
}
