//! The sign of an exact predicate. Decisions are taken on signs, never on
//! products of predicate values (a product of two orient3d values is a
//! degree-6 polynomial and overflows or rounds where the signs do not).

/// Sign of a predicate value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    Negative,
    Zero,
    Positive,
}

impl Sign {
    /// Sign of an f64 (which must not be NaN).
    #[inline]
    pub fn of_f64(v: f64) -> Sign {
        if v > 0.0 {
            Sign::Positive
        } else if v < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }

    /// Sign of an i128.
    #[inline]
    pub fn of_i128(v: i128) -> Sign {
        match v.cmp(&0) {
            std::cmp::Ordering::Greater => Sign::Positive,
            std::cmp::Ordering::Less => Sign::Negative,
            std::cmp::Ordering::Equal => Sign::Zero,
        }
    }

    #[inline]
    pub fn flip(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }

    #[inline]
    pub fn is_positive(self) -> bool {
        self == Sign::Positive
    }
    #[inline]
    pub fn is_negative(self) -> bool {
        self == Sign::Negative
    }
    #[inline]
    pub fn is_zero(self) -> bool {
        self == Sign::Zero
    }
}
