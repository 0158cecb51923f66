//! Axes: linear and logarithmic scales, ranges and tick labels.

/// How an axis maps values to the page.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Evenly spaced values.
    Linear,
    /// Decades evenly spaced; ticks at powers of ten. Values ≤ 0 are not drawn.
    Log10,
    /// Octaves evenly spaced; ticks at powers of two. Values ≤ 0 are not drawn.
    Log2,
}

impl Scale {
    pub(super) fn forward(self, v: f64) -> Option<f64> {
        let t = match self {
            Scale::Linear => v,
            Scale::Log10 if v > 0.0 => v.log10(),
            Scale::Log2 if v > 0.0 => v.log2(),
            _ => return None,
        };
        t.is_finite().then_some(t)
    }

    pub(super) fn inverse(self, t: f64) -> f64 {
        match self {
            Scale::Linear => t,
            Scale::Log10 => 10f64.powf(t),
            Scale::Log2 => t.exp2(),
        }
    }
}

/// One axis: its label (with units), scale, optional range and tick format.
#[derive(Clone, Debug)]
pub struct Axis {
    pub(super) label: String,
    pub(super) scale: Scale,
    pub(super) range: Option<(f64, f64)>,
    pub(super) format: Option<fn(f64) -> String>,
}

impl Axis {
    /// A linear axis labelled `label` (put the units in it: "depth (m)").
    pub fn linear(label: impl Into<String>) -> Self {
        Self {
            label: label.into(),
            scale: Scale::Linear,
            range: None,
            format: None,
        }
    }

    /// A base-10 logarithmic axis.
    pub fn log10(label: impl Into<String>) -> Self {
        Self {
            scale: Scale::Log10,
            ..Self::linear(label)
        }
    }

    /// A base-2 logarithmic axis (texture sizes, say).
    pub fn log2(label: impl Into<String>) -> Self {
        Self {
            scale: Scale::Log2,
            ..Self::linear(label)
        }
    }

    /// Fixes the range (in data units); otherwise it fits the data. On log
    /// axes the range widens to whole decades (octaves).
    pub fn range(mut self, lo: f64, hi: f64) -> Self {
        self.range = Some((lo, hi));
        self
    }

    /// Formats tick values (data units). Defaults: plain numbers on linear
    /// axes, `10⁻³`-style powers on log10 axes, plain numbers on log2 axes.
    pub fn format(mut self, f: fn(f64) -> String) -> Self {
        self.format = Some(f);
        self
    }

    pub(super) fn tick_label(&self, t: f64) -> String {
        match self.scale {
            Scale::Linear => match self.format {
                Some(f) => f(t),
                None => linear_label(t),
            },
            Scale::Log10 | Scale::Log2 => {
                if (t - t.round()).abs() > 1e-6 {
                    return String::new();
                }
                let v = self.scale.inverse(t.round());
                match (self.format, self.scale) {
                    (Some(f), _) => f(v),
                    (None, Scale::Log10) => power_of_ten(t.round() as i32),
                    _ => linear_label(v),
                }
            }
        }
    }
}

/// A plain tick label: no trailing zeros, no `-0`.
fn linear_label(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// `10⁻³`, `10⁰`, `10²`.
pub fn power_of_ten(k: i32) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::from("10");
    if k < 0 {
        s.push('⁻');
    }
    for c in k.unsigned_abs().to_string().chars() {
        s.push(SUP[c.to_digit(10).unwrap_or(0) as usize]);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels() {
        assert_eq!(power_of_ten(-3), "10⁻³");
        assert_eq!(power_of_ten(12), "10¹²");
        assert_eq!(linear_label(0.25), "0.25");
        assert_eq!(linear_label(-0.0), "0");
        assert_eq!(Axis::log10("").tick_label(-2.0), "10⁻²");
        assert_eq!(Axis::log10("").tick_label(-2.5), "");
        assert_eq!(Axis::log2("").tick_label(5.0), "32");
    }
}
