//! Numbers written as text without `core::fmt`, for the OBJ writer: a refined mesh is millions
//! of floats and indices, and through `write!` the formatting machinery took about half of the
//! write (a 160 MB OBJ of the horse at level 2 with normals: 1.16 s). Numbers are written into
//! arrays of known length and appended whole (see [`push_u64`]): 550 → 355-430 ms for that
//! file to `/dev/null`, the text unchanged byte for byte.

/// Appends `n` in decimal.
pub(crate) fn push_u64(out: &mut Vec<u8>, n: u64) {
    // Written left-aligned and appended as a whole array, then cut to its digits: a copy of a
    // known length is a few stores, where one of the digits' own length was a `memcpy` call per
    // number (about a tenth of a large OBJ's write).
    let mut digits = [b'0'; 20];
    let count = n.checked_ilog10().map_or(1, |k| k as usize + 1);
    let (mut rest, mut end) = (n, count);
    // Two digits a step, from a table.
    while end >= 2 {
        let pair = (rest % 100) as usize * 2;
        digits[end - 2..end].copy_from_slice(&PAIRS[pair..pair + 2]);
        rest /= 100;
        end -= 2;
    }
    if end == 1 {
        digits[0] = b'0' + rest as u8;
    }
    append_prefix(out, &digits, count);
}

/// "00" to "99", each pair at twice its value.
const PAIRS: &[u8; 200] = b"0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// Appends the first `count` bytes of `bytes` (appended whole, then cut: see [`push_u64`]).
#[inline(always)]
fn append_prefix<const N: usize>(out: &mut Vec<u8>, bytes: &[u8; N], count: usize) {
    let at = out.len();
    out.extend_from_slice(bytes);
    out.truncate(at + count.min(N));
}

/// Appends `x` as `format!("{x}")` writes it: the shortest decimal that reads back as `x`, in
/// positional notation (never an exponent), `-0` for negative zero, `NaN`, `inf` and `-inf`.
/// The digits come from Ryū (Adams, "Ryū: fast float-to-string conversion", PLDI 2018); only
/// their placement is done here. Where two shortest decimals are equally close to `x`, Ryū
/// takes the even last digit and the standard library the upper one (`-2110626.2` against
/// `-2110626.3` for `-2110626.25`): both read back as `x`.
pub(crate) fn push_f32(out: &mut Vec<u8>, x: f32) {
    if !x.is_finite() {
        let text: &[u8] = if x.is_nan() {
            b"NaN"
        } else if x > 0.0 {
            b"inf"
        } else {
            b"-inf"
        };
        out.extend_from_slice(text);
        return;
    }
    // Written straight into an array of known length (`ryu::Buffer` handed back a slice of its
    // own, whose copy out was a `memcpy` call per number); the zeros after the text are never
    // an `e`.
    let mut fixed = [0u8; 24];
    // SAFETY: `format32` needs room for Ryū's text of a finite `x` (at most 16 bytes: its
    // documentation's example gives 16) and `fixed` holds 24, as `ryu::Buffer` does.
    let count = unsafe { ryu::raw::format32(x, fixed.as_mut_ptr()) }.min(fixed.len());
    let text = &fixed[..count];
    if !fixed.contains(&b'e') {
        // Positional already (Ryū's notation for 1e-5 < |x| < 1e13), with `.0` after whole
        // numbers, which `Display` leaves out.
        let whole = count >= 2 && fixed[count - 2..count] == *b".0";
        append_prefix(out, &fixed, if whole { count - 2 } else { count });
        return;
    }
    let (negative, text) = match text.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, text),
    };
    // `d.ddde±k` or `de±k`: collect the significant digits and where the decimal point falls
    // among them.
    let (mantissa, exponent) = match text.iter().position(|&c| c == b'e') {
        Some(e) => (&text[..e], parse_exponent(&text[e + 1..])),
        None => (text, 0),
    };
    // Ryū writes at most 16 bytes for an f32.
    let mut digits = [0u8; 24];
    let mut count = 0;
    let mut point = None;
    for &c in mantissa {
        if c == b'.' {
            point = Some(count);
        } else if count < digits.len() {
            digits[count] = c;
            count += 1;
        }
    }
    let mut point = point.unwrap_or(count) as i32 + exponent;
    let mut first = 0;
    while first < count && digits[first] == b'0' {
        first += 1;
        point -= 1;
    }
    while count > first && digits[count - 1] == b'0' {
        count -= 1;
    }
    let digits = &digits[first..count];
    if negative {
        out.push(b'-');
    }
    if digits.is_empty() {
        out.push(b'0');
    } else if point <= 0 {
        out.extend_from_slice(b"0.");
        out.extend(std::iter::repeat_n(b'0', point.unsigned_abs() as usize));
        out.extend_from_slice(digits);
    } else if point as usize >= digits.len() {
        out.extend_from_slice(digits);
        out.extend(std::iter::repeat_n(b'0', point as usize - digits.len()));
    } else {
        let (whole, fraction) = digits.split_at(point as usize);
        out.extend_from_slice(whole);
        out.push(b'.');
        out.extend_from_slice(fraction);
    }
}

/// The exponent after Ryū's `e`: an optional `-` and decimal digits.
fn parse_exponent(text: &[u8]) -> i32 {
    let (sign, digits) = match text.split_first() {
        Some((b'-', rest)) => (-1, rest),
        _ => (1, text),
    };
    sign * digits.iter().fold(0i32, |k, &d| k * 10 + i32::from(d.wrapping_sub(b'0')))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn float(x: f32) -> String {
        let mut out = Vec::new();
        push_f32(&mut out, x);
        String::from_utf8(out).unwrap()
    }

    /// The reference is the standard library: its `Display` (which the OBJ writer used before)
    /// gives the length and the notation, and its parser must read the text back as `x`.
    fn check(x: f32) {
        let text = float(x);
        let display = format!("{x}");
        if x.is_nan() {
            assert_eq!(text, display);
            return;
        }
        assert_eq!(text.len(), display.len(), "{text} against {display}");
        assert_eq!(text.parse::<f32>().map(f32::to_bits), Ok(x.to_bits()), "{text} for {x:e}");
        assert!(!text.contains('e'), "{text}");
        if text != display {
            // A tie between two shortest decimals: they differ in the last digit only.
            let (a, b) = (text.as_bytes(), display.as_bytes());
            let last = a.len() - 1;
            assert_eq!(a[..last], b[..last], "{text} against {display}");
            assert_eq!(a[last].abs_diff(b[last]), 1, "{text} against {display}");
        }
    }

    #[test]
    fn floats_read_back_and_are_as_short_as_display() {
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            0.5,
            10.0,
            100.0,
            1e7,
            1.5e7,
            123456.79,
            1e-5,
            1e-7,
            -3.25e-3,
            f32::MIN_POSITIVE,
            f32::from_bits(1),
            f32::MAX,
            f32::MIN,
            f32::EPSILON,
            16777216.0,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        for x in special {
            check(x);
        }
        // Bit patterns spread over every exponent (a fixed xorshift sequence).
        let mut state = 0x9e37_79b9_u32;
        for _ in 0..1_000_000 {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            let x = f32::from_bits(state);
            check(x);
        }
    }

    #[test]
    fn integers_read_as_display_writes_them() {
        // Every count of digits (each power of ten and its neighbours), the first thousand,
        // and a pseudo-random sweep, appended after other text.
        let powers = (0..20).map(|k| 10u64.pow(k));
        let edges = powers.flat_map(|p| [p - 1, p, p + 1]);
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let sweep = (0..10_000).map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state >> (state % 64)
        });
        let special = [12345, u32::MAX as u64, u64::MAX];
        for n in edges.chain(0..1000).chain(sweep).chain(special) {
            let mut out = b"f ".to_vec();
            push_u64(&mut out, n);
            assert_eq!(String::from_utf8(out).unwrap(), format!("f {n}"));
        }
    }
}
