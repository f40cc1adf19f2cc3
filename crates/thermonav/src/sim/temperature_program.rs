//! A temperature program: a table of (time since the start, temperature), linear between its
//! rows and held at its end values outside them. It drives a survey's sensor temperature
//! (`simulate vessel --temperature-file`) and a chamber's (`simulate chamber
//! --temperature-file`: cool, heat, cool at stated rates, dwells as flat stretches).

use serde::Serialize;

/// A table of (time since the start, temperature).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TemperatureProgram {
    /// Times since the start, s, strictly increasing.
    pub t_s: Vec<f64>,
    /// Temperatures, °C.
    pub temperature_c: Vec<f64>,
}

impl TemperatureProgram {
    /// The temperature `t_s` after the start, °C (the end values held outside the table; the
    /// mean of nothing for an empty table is never asked: see [`Self::is_valid`]).
    pub fn at(&self, t_s: f64) -> f64 {
        let (xs, ys) = (&self.t_s, &self.temperature_c);
        let k = xs.partition_point(|&v| v <= t_s);
        match k {
            0 => ys.first().copied().unwrap_or(f64::NAN),
            k if k == xs.len() => ys[k - 1],
            k => {
                let w = (t_s - xs[k - 1]) / (xs[k] - xs[k - 1]);
                ys[k - 1] + w * (ys[k] - ys[k - 1])
            }
        }
    }

    /// True for a non-empty table of equal columns, finite values and increasing times.
    pub fn is_valid(&self) -> bool {
        !self.t_s.is_empty()
            && self.t_s.len() == self.temperature_c.len()
            && self
                .t_s
                .iter()
                .chain(&self.temperature_c)
                .all(|v| v.is_finite())
            && self.t_s.windows(2).all(|w| w[0] < w[1])
    }

    /// Time of the last row, s (0 for an empty table).
    pub fn end_s(&self) -> f64 {
        self.t_s.last().copied().unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_program_is_linear_between_rows_and_held_outside() {
        let p = TemperatureProgram {
            t_s: vec![10.0, 70.0, 100.0],
            temperature_c: vec![20.0, -10.0, -10.0],
        };
        assert!(p.is_valid());
        assert_eq!(p.at(0.0), 20.0);
        assert_eq!(p.at(40.0), 5.0);
        assert_eq!(p.at(85.0), -10.0);
        assert_eq!(p.at(500.0), -10.0);
        assert_eq!(p.end_s(), 100.0);
        let unordered = TemperatureProgram {
            t_s: vec![0.0, 0.0],
            temperature_c: vec![1.0, 2.0],
        };
        assert!(!unordered.is_valid());
    }
}
