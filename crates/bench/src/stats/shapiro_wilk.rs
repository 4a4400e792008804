//! Shapiro–Wilk test of normality (Shapiro & Wilk 1965) with Royston's approximations
//! (Royston 1992/1995, Algorithm AS R94), ported from SciPy 1.17's `swilk` (`scipy.stats.shapiro`).
//!
//! - The sample is sorted and shifted by x[n/2] of the *unsorted* input, as SciPy does (it only
//!   changes rounding; W is shift-invariant).
//! - Coefficients aᵢ from Royston's polynomial corrections to the normal scores m̃ᵢ =
//!   Φ⁻¹((i − 3/8)/(n + 1/4)), with Φ⁻¹ by AS 111 (`ppnd`, about 7 digits, as in AS R94 and SciPy);
//!   W = (Σ aᵢ x₍ᵢ₎)² / Σ (xᵢ − x̄)², computed in AS R94's cancellation-safe form.
//! - p: exact for n = 3 (p = 1 − (6/π)·acos(√W), W clamped to ≥ 3/4); otherwise Royston's normal
//!   approximation of ln(1 − W) (n ≤ 11: −ln(γ − ln(1 − W)) with γ = −2.273 + 0.459 n, and
//!   p = 1e-19 when ln(1 − W) ≥ γ), upper tail by AS 66 (`alnorm`) as SciPy.
//! - Zero range (all values equal): W = 1, p = 1, `MethodUsed::Degenerate` (SciPy warns and
//!   returns the same). No censoring (AS R94's n1 < n) is supported, as in SciPy. For n > 5000
//!   the approximation is outside Royston's validated range (SciPy warns); we still compute it.

use super::{MethodUsed, StatsError, check};

/// Result of a Shapiro–Wilk test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapiroWilk {
    /// The W statistic (1 = perfectly normal-looking).
    pub w: f64,
    /// p-value of H₀ "the sample comes from a normal distribution".
    pub p_value: f64,
    /// `Exact` (n = 3), `Royston` or `Degenerate` (zero range).
    pub method: MethodUsed,
}

const C1: [f64; 6] = [
    0.0,
    0.221157,
    -0.147981,
    -0.207119e1,
    0.4434685e1,
    -0.2706056e1,
];
const C2: [f64; 6] = [
    0.0,
    0.42981e-1,
    -0.293762,
    -0.1752461e1,
    0.5682633e1,
    -0.3582633e1,
];
const C3: [f64; 4] = [0.5440, -0.39978, 0.25054e-1, -0.6714e-3];
const C4: [f64; 4] = [0.13822e1, -0.77857, 0.62767e-1, -0.20322e-2];
const C5: [f64; 4] = [-0.15861e1, -0.31082, -0.83751e-1, 0.38915e-2];
const C6: [f64; 3] = [-0.4803, -0.82676e-1, 0.30302e-2];
const G: [f64; 2] = [-0.2273e1, 0.459];
const SMALL: f64 = 1e-19;

/// Shapiro–Wilk W and p-value of a finite sample with at least 3 values.
pub fn shapiro_wilk(x: &[f64]) -> Result<ShapiroWilk, StatsError> {
    check(x)?;
    let n = x.len();
    if n < 3 {
        return Err(StatsError::TooFew { need: 3, got: n });
    }
    let mut y = x.to_vec();
    y.sort_by(f64::total_cmp);
    let shift = x[n / 2];
    for v in &mut y {
        *v -= shift;
    }
    let nn2 = n / 2;
    let an = n as f64;
    let mut a = vec![0.0f64; nn2];
    if n == 3 {
        a[0] = std::f64::consts::FRAC_1_SQRT_2;
    } else {
        let an25 = an + 0.25;
        let mut summ2 = 0.0;
        for (i, ai) in a.iter_mut().enumerate() {
            *ai = ppnd((i as f64 + 1.0 - 0.375) / an25);
            summ2 += *ai * *ai;
        }
        summ2 *= 2.0;
        let ssumm2 = summ2.sqrt();
        let rsn = 1.0 / an.sqrt();
        let a1 = poly(&C1, rsn) - a[0] / ssumm2;
        let (i1, fac) = if n > 5 {
            let a2 = -a[1] / ssumm2 + poly(&C2, rsn);
            let fac = ((summ2 - 2.0 * a[0] * a[0] - 2.0 * a[1] * a[1])
                / (1.0 - 2.0 * a1 * a1 - 2.0 * a2 * a2))
                .sqrt();
            a[1] = a2;
            (2, fac)
        } else {
            (
                1,
                ((summ2 - 2.0 * a[0] * a[0]) / (1.0 - 2.0 * a1 * a1)).sqrt(),
            )
        };
        a[0] = a1;
        for ai in &mut a[i1..] {
            *ai *= -1.0 / fac;
        }
    }
    let range = y[n - 1] - y[0];
    if range < SMALL {
        return Ok(ShapiroWilk {
            w: 1.0,
            p_value: 1.0,
            method: MethodUsed::Degenerate,
        });
    }
    // Coefficient of the i-th order statistic: −a[i] in the lower half, +a[n−1−i] in the
    // upper half, 0 for the middle of an odd sample.
    let coef = |i: usize| -> f64 {
        let j = n - 1 - i;
        match i.cmp(&j) {
            std::cmp::Ordering::Less => -a[i],
            std::cmp::Ordering::Greater => a[j],
            std::cmp::Ordering::Equal => 0.0,
        }
    };
    let (mut sa, mut sx) = (0.0, 0.0);
    for (i, v) in y.iter().enumerate() {
        sx += v / range;
        sa += coef(i);
    }
    sa /= an;
    sx /= an;
    let (mut ssa, mut ssx, mut sax) = (0.0, 0.0, 0.0);
    for (i, v) in y.iter().enumerate() {
        let asa = coef(i) - sa;
        let xsx = v / range - sx;
        ssa += asa * asa;
        ssx += xsx * xsx;
        sax += asa * xsx;
    }
    let ssassx = (ssa * ssx).sqrt();
    let w1 = (ssassx - sax) * (ssassx + sax) / (ssa * ssx);
    let w = 1.0 - w1;
    if n == 3 {
        if w < 0.75 {
            return Ok(ShapiroWilk {
                w: 0.75,
                p_value: 0.0,
                method: MethodUsed::Exact,
            });
        }
        let p = 1.0 - 6.0 / std::f64::consts::PI * w.sqrt().acos();
        return Ok(ShapiroWilk {
            w,
            p_value: p,
            method: MethodUsed::Exact,
        });
    }
    let mut yy = w1.ln();
    let lnn = an.ln();
    let (m, s) = if n <= 11 {
        let gamma = poly(&G, an);
        if yy >= gamma {
            return Ok(ShapiroWilk {
                w,
                p_value: SMALL,
                method: MethodUsed::Royston,
            });
        }
        yy = -(gamma - yy).ln();
        (poly(&C3, an), poly(&C4, an).exp())
    } else {
        (poly(&C5, lnn), poly(&C6, lnn).exp())
    };
    Ok(ShapiroWilk {
        w,
        p_value: alnorm_upper((yy - m) / s),
        method: MethodUsed::Royston,
    })
}

/// c₀ + c₁x + c₂x² + … (AS R94's `poly`).
fn poly(c: &[f64], x: f64) -> f64 {
    let nord = c.len();
    if nord == 1 {
        return c[0];
    }
    let mut p = x * c[nord - 1];
    if nord > 2 {
        for &ci in c[1..nord - 1].iter().rev() {
            p = (p + ci) * x;
        }
    }
    c[0] + p
}

/// Upper normal tail 1 − Φ(x) by Hill's Algorithm AS 66 (`alnorm`, upper = true), as SciPy's swilk.
fn alnorm_upper(x: f64) -> f64 {
    const LTONE: f64 = 7.0;
    const UTZERO: f64 = 38.0;
    const CON: f64 = 1.28;
    let mut upper = true;
    let mut z = x;
    if z.is_nan() || z <= 0.0 {
        upper = false;
        z = -z;
    }
    if !(z <= LTONE || (upper && z <= UTZERO)) {
        return if upper { 0.0 } else { 1.0 };
    }
    let y = 0.5 * z * z;
    let temp = if z <= CON {
        0.5 - z
            * (0.398942280444
                - 0.399903438504 * y
                    / (y + 5.75885480458
                        - 29.8213557808
                            / (y + 2.62433121679 + 48.6959930692 / (y + 5.92885724438))))
    } else {
        0.398942280385 * (-y).exp()
            / (z - 3.8052e-8
                + 1.00000615302
                    / (z + 3.98064794e-4
                        + 1.98615381364
                            / (z - 0.151679116635
                                + 5.29330324926
                                    / (z + 4.8385912808
                                        - 15.1508972451
                                            / (z + 0.742380924027
                                                + 30.789933034 / (z + 3.99019417011))))))
    };
    if upper { temp } else { 1.0 - temp }
}

/// Normal quantile Φ⁻¹(p) by Beasley & Springer's Algorithm AS 111 (`ppnd`), as AS R94 uses it.
fn ppnd(p: f64) -> f64 {
    let q = p - 0.5;
    if q.abs() <= 0.42 {
        let r = q * q;
        let num =
            q * (((-25.44106049637 * r + 41.39119773534) * r - 18.61500062529) * r + 2.50662823884);
        let den = (((3.13082909833 * r - 21.06224101826) * r + 23.08336743743) * r - 8.47351093090)
            * r
            + 1.0;
        return num / den;
    }
    let mut r = if q > 0.0 { 1.0 - p } else { p };
    if r > 0.0 {
        r = (-r.ln()).sqrt();
    } else {
        return 0.0;
    }
    let num = ((2.32121276858 * r + 4.85014127135) * r - 2.29796479134) * r - 2.78718931138;
    let den = (1.63706781897 * r + 3.54388924762) * r + 1.0;
    let t = num / den;
    if q < 0.0 { -t } else { t }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn n3_exact_and_degenerate() {
        // Equally spaced triple: W = 1, p = 1.
        let r = shapiro_wilk(&[1.0, 2.0, 3.0]).unwrap();
        assert!((r.w - 1.0).abs() < 1e-12 && (r.p_value - 1.0).abs() < 1e-6);
        let r = shapiro_wilk(&[5.0; 8]).unwrap();
        assert_eq!(
            (r.w, r.p_value, r.method),
            (1.0, 1.0, MethodUsed::Degenerate)
        );
        assert_eq!(
            shapiro_wilk(&[1.0, 2.0]),
            Err(StatsError::TooFew { need: 3, got: 2 })
        );
    }
}
