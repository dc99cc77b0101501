//! Quantities with the units engineers use: accelerations in gal, g or m/s2, lengths in mm, cm
//! or m. Everything inside pirqa is SI (m, s, kg, N); these functions are the only way in, and
//! [`Shown`] is how a message writes a number back out.

/// The value of one g used to convert accelerations given in g (m/s2). The paper, the wall files
/// and most record processing (PEER: 981 cm/s2) use 9.81; standard gravity 9.80665 differs by
/// 0.03 %.
pub const G_UNIT_M_S2: f64 = 9.81;

/// One gal in m/s2.
pub const GAL_M_S2: f64 = 0.01;

/// Units of acceleration accepted on input.
pub const ACCELERATION_UNITS: &str = "gal, g, m/s2 (e.g. 400gal, 0.41g, 4.0m/s2)";

/// Units of length accepted on input.
pub const LENGTH_UNITS: &str = "mm, cm, m (e.g. 5mm, 0.5cm, 0.005m)";

/// A quantity with units could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnitError {
    /// Not a number followed by a known unit.
    #[error("cannot read {what} \"{text}\": write a number and a unit, one of {units}")]
    Unreadable {
        /// What was expected (acceleration, length...).
        what: &'static str,
        /// The text given.
        text: String,
        /// The units accepted.
        units: &'static str,
    },
}

/// A number as a message shows it: as Rust writes it where that is short, in exponent form
/// where it is very large or very small (1e300, not its 301 digits; 1e-300, not 300 zeros).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shown(pub f64);

impl std::fmt::Display for Shown {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&x.abs()) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// [`Shown`] of a borrowed number, for error messages' fields.
pub fn shown(x: &f64) -> Shown {
    Shown(*x)
}

/// A unit of acceleration.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AccelUnit {
    /// cm/s2.
    Gal,
    /// Multiples of [`G_UNIT_M_S2`].
    G,
    /// m/s2.
    #[serde(rename = "m/s2")]
    Ms2,
}

impl AccelUnit {
    /// Metres per second squared in one of this unit.
    pub fn to_m_s2(self) -> f64 {
        match self {
            AccelUnit::Gal => GAL_M_S2,
            AccelUnit::G => G_UNIT_M_S2,
            AccelUnit::Ms2 => 1.0,
        }
    }

    /// Reads a unit name: `gal`, `g`, `m/s2` (also `m/s^2`, `mps2`, `cm/s2`).
    pub fn parse(s: &str) -> Option<AccelUnit> {
        match s.trim().to_ascii_lowercase().as_str() {
            "gal" | "gals" | "cm/s2" | "cm/s^2" | "cm/s/s" => Some(AccelUnit::Gal),
            "g" => Some(AccelUnit::G),
            "m/s2" | "m/s^2" | "mps2" | "m/s/s" => Some(AccelUnit::Ms2),
            _ => None,
        }
    }

    /// The unit's name as written in files and output.
    pub fn name(self) -> &'static str {
        match self {
            AccelUnit::Gal => "gal",
            AccelUnit::G => "g",
            AccelUnit::Ms2 => "m/s2",
        }
    }
}

fn split_number(text: &str) -> Option<(f64, &str)> {
    let t = text.trim();
    let end = t
        .char_indices()
        .find(|&(i, c)| {
            !(c.is_ascii_digit()
                || c == '.'
                || c == '+'
                || c == '-'
                || ((c == 'e' || c == 'E')
                    && t[i + 1..]
                        .starts_with(|d: char| d.is_ascii_digit() || d == '-' || d == '+')))
        })
        .map_or(t.len(), |(i, _)| i);
    let value: f64 = t[..end].parse().ok()?;
    value.is_finite().then_some((value, t[end..].trim()))
}

/// Reads an acceleration such as `400gal`, `0.41g` or `4.0 m/s2` and returns m/s2.
pub fn parse_acceleration(text: &str) -> Result<f64, UnitError> {
    let err = || UnitError::Unreadable {
        what: "acceleration",
        text: text.to_string(),
        units: ACCELERATION_UNITS,
    };
    let (value, unit) = split_number(text).ok_or_else(err)?;
    let unit = AccelUnit::parse(unit).ok_or_else(err)?;
    Ok(value * unit.to_m_s2())
}

/// Reads a length such as `5mm`, `0.5 cm` or `0.005m` and returns metres.
pub fn parse_length(text: &str) -> Result<f64, UnitError> {
    let err = || UnitError::Unreadable {
        what: "length",
        text: text.to_string(),
        units: LENGTH_UNITS,
    };
    let (value, unit) = split_number(text).ok_or_else(err)?;
    Ok(value * length_unit_m(unit).ok_or_else(err)?)
}

/// Metres in one `mm`, `cm` or `m` (any case).
pub fn length_unit_m(unit: &str) -> Option<f64> {
    match unit.to_ascii_lowercase().as_str() {
        "mm" => Some(1e-3),
        "cm" => Some(1e-2),
        "m" => Some(1.0),
        _ => None,
    }
}

#[cfg(test)]
mod tests {

    #[test]
    fn a_message_shows_huge_and_tiny_numbers_in_exponent_form() {
        for (x, text) in [
            (0.0, "0"),
            (0.05, "0.05"),
            (-400.0, "-400"),
            (1e-5, "0.00001"),
            (1e-6, "1e-6"),
            (-1e300, "-1e300"),
            (1.5e-300, "1.5e-300"),
            (1e16, "1e16"),
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
        ] {
            assert_eq!(Shown(x).to_string(), text);
        }
    }

    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn accelerations_in_engineering_units() {
        assert_relative_eq!(
            parse_acceleration("400gal").unwrap(),
            4.0,
            max_relative = 1e-15
        );
        assert_relative_eq!(parse_acceleration("0.41g").unwrap(), 0.41 * 9.81);
        assert_relative_eq!(parse_acceleration("4.0m/s2").unwrap(), 4.0);
        assert_relative_eq!(parse_acceleration(" 2.5e2 gal ").unwrap(), 2.5);
        assert_relative_eq!(parse_acceleration("-3 m/s^2").unwrap(), -3.0);
        for bad in ["400", "gal", "4 km/s2", "nan gal", "1e400gal", ""] {
            let e = parse_acceleration(bad).unwrap_err().to_string();
            assert!(e.contains("gal, g, m/s2"), "{bad}: {e}");
        }
    }

    #[test]
    fn lengths_in_engineering_units() {
        assert_relative_eq!(parse_length("5mm").unwrap(), 0.005);
        assert_relative_eq!(parse_length("0.5 cm").unwrap(), 0.005);
        assert_relative_eq!(parse_length("2m").unwrap(), 2.0);
        assert!(parse_length("5 inch").is_err());
    }
}
