//! Number formatting and titles that fit.

/// `x` to `digits` significant digits, trailing zeros trimmed; scientific outside [1e-3, 1e5).
pub fn sig(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { "0".into() } else { format!("{x}") };
    }
    let e = x.abs().log10().floor() as i32;
    if !(-3..5).contains(&e) {
        let s = format!("{:.*e}", digits.saturating_sub(1), x);
        // 1.50e-5 → 1.5e-5
        return match s.split_once('e') {
            Some((m, exp)) => format!("{}e{exp}", trim(m)),
            None => s,
        };
    }
    let decimals = (digits as i32 - 1 - e).max(0) as usize;
    trim(&format!("{x:.decimals$}")).to_string()
}

/// Trailing zeros (and a trailing dot) of a decimal number removed.
fn trim(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

/// A table row: `lead`, then each `(text, width)` cell right-aligned at the end of its
/// column, one space after the column before. A cell wider than its column takes the padding
/// of the cells after it (at least one space stays), so that one long value (h at level 7)
/// shifts its row only as far as it must instead of pushing it out of its panel.
pub fn table_row(lead: &str, cells: &[(&str, usize)]) -> String {
    let mut out = String::from(lead);
    let (mut len, mut end) = (lead.chars().count(), lead.chars().count());
    for &(text, width) in cells {
        end += 1 + width;
        let n = text.chars().count();
        let pad = end.saturating_sub(len + n).max(1);
        out.push_str(&" ".repeat(pad));
        out.push_str(text);
        len += pad + n;
    }
    out
}

/// `text` cut to `width` characters, ending with "…" when cut (block titles).
pub fn title_fit(text: &str, width: u16) -> String {
    let width = usize::from(width);
    if text.chars().count() <= width {
        return text.to_string();
    }
    let mut out: String = text.chars().take(width.saturating_sub(2)).collect();
    // At the last word boundary when there is one in the second half.
    if let Some(space) = out.trim_end().rfind(' ')
        && out[..space].chars().count() > width / 2
    {
        out.truncate(space);
    }
    out = out.trim_end().to_string();
    out.push_str("… ");
    out
}

/// `text` wrapped at spaces to lines of at most `width` characters (a longer word is split);
/// the text's own line breaks are kept.
pub fn wrap_words(text: &str, width: usize) -> Vec<String> {
    let width = width.max(1);
    let mut out = Vec::new();
    for line in text.lines() {
        let mut current = String::new();
        for word in line.split(' ') {
            let mut word: String = word.to_string();
            loop {
                let (cw, ww) = (current.chars().count(), word.chars().count());
                if cw > 0 && cw + 1 + ww <= width {
                    current.push(' ');
                    current.push_str(&word);
                    break;
                }
                if cw == 0 && ww <= width {
                    current = word;
                    break;
                }
                if cw > 0 {
                    out.push(std::mem::take(&mut current));
                    continue;
                }
                // A word longer than a line: split it.
                let head: String = word.chars().take(width).collect();
                word = word.chars().skip(width).collect();
                out.push(head);
            }
        }
        out.push(current);
    }
    out
}

/// `text` of items joined by ` · ` wrapped to lines of at most `width` characters between
/// items, so that no item ("1 iteration", "P = 7.5") is split; an item longer than a line is
/// wrapped at its spaces ([`wrap_words`]).
pub fn wrap_items(text: &str, width: usize) -> Vec<String> {
    const SEP: &str = " · ";
    let mut out: Vec<String> = Vec::new();
    let mut current = String::new();
    for item in text.split(SEP) {
        let (cw, iw) = (current.chars().count(), item.chars().count());
        if cw > 0 && cw + SEP.chars().count() + iw <= width {
            current.push_str(SEP);
            current.push_str(item);
            continue;
        }
        if cw > 0 {
            out.push(std::mem::take(&mut current));
        }
        if iw <= width {
            current = item.to_string();
        } else {
            out.extend(wrap_words(item, width));
        }
    }
    if !current.is_empty() || out.is_empty() {
        out.push(current);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::nice_ceil;

    /// Items stay whole: the line breaks between them, and an item wider than a line is
    /// wrapped at its spaces.
    #[test]
    fn items_are_wrapped_whole() {
        let text = "rip-trapezoid: load P = 3.032e-298 · p max 7.338e-298 · contact 0 to 0.5 · 1 iteration";
        assert_eq!(
            wrap_items(text, 79),
            [
                "rip-trapezoid: load P = 3.032e-298 · p max 7.338e-298 · contact 0 to 0.5",
                "1 iteration"
            ]
        );
        assert_eq!(wrap_items("a · b", 80), ["a · b"]);
        assert_eq!(wrap_items("a long item · b", 6), ["a long", "item", "b"]);
        assert_eq!(wrap_items("", 6), [""]);
    }

    #[test]
    fn a_table_row_is_the_columns_format_and_a_long_cell_borrows_padding() {
        let cells = [("0.0156", 6), ("3e-4", 9), ("1.07", 9)];
        assert_eq!(
            table_row("▸ 6", &cells),
            format!("▸ 6 {:>6} {:>9} {:>9}", "0.0156", "3e-4", "1.07")
        );
        // One character too long: the next cell's padding gives way, the row's end stays.
        let long = table_row("▸ 7", &[("0.00781", 6), ("1.06e-4", 9), ("1.07", 9)]);
        assert_eq!(long, "▸ 7 0.00781  1.06e-4      1.07");
        assert_eq!(long.chars().count(), table_row("▸ 6", &cells).chars().count());
        // Too long to absorb: one space always separates cells.
        assert_eq!(table_row("", &[("abcd", 2), ("ef", 2)]), " abcd ef");
    }

    #[test]
    fn significant_digits() {
        assert_eq!(sig(0.0, 3), "0");
        assert_eq!(sig(12.3456, 3), "12.3");
        assert_eq!(sig(1.5e-5, 3), "1.5e-5");
        assert_eq!(sig(0.5, 3), "0.5");
        assert_eq!(sig(-8.0, 3), "-8");
        assert_eq!(nice_ceil(11.0), 12.0);
        assert_eq!(title_fit(" a long title ", 8), " a lon… ");
        assert_eq!(title_fit(" a long title here ", 16), " a long title… ");
        assert_eq!(title_fit(" short ", 8), " short ");
        assert_eq!(wrap_words("one two three", 7), ["one two", "three"]);
        assert_eq!(wrap_words("abcdefghij", 4), ["abcd", "efgh", "ij"]);
        assert_eq!(wrap_words("a\nb c", 9), ["a", "b c"]);
    }
}
