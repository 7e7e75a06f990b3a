//! The tour shows every number its captions quote. For every step of the
//! embedded tour at 80×24 and 100×30, each number of the caption (equation references such as
//! "(17)" and the digits of names such as M1, Q1 or γ₀ aside) appears in the lab's part of the
//! frame, above the caption panel, to the digits it is quoted with: "479" is met by a shown
//! "478.75", "2.9e-2" by "0.0293".

use riplab::tui::tour::Tour;

use super::{PAPER_SIZES, paper_frames};

/// A number as written: its value and half a unit of its last digit.
#[derive(Debug)]
struct Quoted {
    text: String,
    value: f64,
    half_unit: f64,
}

/// The numbers written in `text` ("1e-6", "0.148", "642"; a "−" before one is not part of it).
/// `in_words` keeps only those a reader takes for a quantity: not the digits of a name (a
/// letter, `_` or `.` before it, a letter after it) nor an equation reference "(17)".
fn numbers(text: &str, in_words: bool) -> Vec<Quoted> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        if !chars[i].is_ascii_digit() {
            i += 1;
            continue;
        }
        let start = i;
        let digits = |i: &mut usize| {
            while *i < chars.len() && chars[*i].is_ascii_digit() {
                *i += 1;
            }
        };
        digits(&mut i);
        let mut decimals = 0;
        if i + 1 < chars.len() && chars[i] == '.' && chars[i + 1].is_ascii_digit() {
            let at = i + 1;
            i += 1;
            digits(&mut i);
            decimals = i - at;
        }
        let mantissa_end = i;
        let mut exponent = 0i32;
        if i + 1 < chars.len() && chars[i] == 'e' {
            let sign = matches!(chars[i + 1], '-' | '−');
            let at = if sign { i + 2 } else { i + 1 };
            if at < chars.len() && chars[at].is_ascii_digit() {
                let mut j = at;
                digits(&mut j);
                let e: i32 = chars[at..j].iter().collect::<String>().parse().unwrap();
                exponent = if sign { -e } else { e };
                i = j;
            }
        }
        let before = if start > 0 { chars[start - 1] } else { ' ' };
        let after = chars.get(i).copied().unwrap_or(' ');
        let name = before.is_alphabetic() || before == '_' || before == '.' || after.is_alphabetic();
        let reference = before == '(' && after == ')';
        if in_words && (name || reference) {
            continue;
        }
        let mantissa: f64 = chars[start..mantissa_end]
            .iter()
            .collect::<String>()
            .parse()
            .unwrap();
        let scale = 10f64.powi(exponent);
        out.push(Quoted {
            text: chars[start..i].iter().collect(),
            value: mantissa * scale,
            half_unit: 0.5 * 10f64.powi(-(decimals as i32)) * scale,
        });
    }
    out
}

/// The caption's numbers that the lab's part of `frame` does not show.
fn missing(caption: &str, frame: &str) -> Vec<String> {
    let lab = frame.split("\n tour ").next().unwrap();
    let shown = numbers(lab, false);
    numbers(caption, true)
        .into_iter()
        .filter(|q| {
            !shown
                .iter()
                .any(|s| (s.value - q.value).abs() <= q.half_unit * (1.0 + 1e-9))
        })
        .map(|q| q.text)
        .collect()
}

#[test]
fn the_matching_reads_numbers_as_written() {
    let quoted: Vec<String> = numbers("M1 at ε = 1e-6, (17): p 0.21, load 479, 2.9e-2 and Q2", true)
        .into_iter()
        .map(|q| q.text)
        .collect();
    assert_eq!(quoted, ["1e-6", "0.21", "479", "2.9e-2"]);
    assert!(missing("load 479", "P=478.75\n tour 1/2").is_empty());
    assert_eq!(missing("load 479", "P=477.9\n tour 1/2"), ["479"]);
    assert!(missing("error 2.9e-2", "err 0.0293\n tour").is_empty());
    assert_eq!(missing("error 2.9e-2", "err 0.0296\n tour"), ["2.9e-2"]);
    // The caption panel itself does not count.
    assert_eq!(missing("β = 0.148", "β 0.15\n tour 2/14 0.148"), ["0.148"]);
}

#[test]
fn every_step_shows_the_numbers_its_caption_quotes() {
    let tour = Tour::paper();
    let mut failures = Vec::new();
    for (i, step) in tour.steps.iter().enumerate() {
        for (&(width, height), frame) in PAPER_SIZES.iter().zip(&paper_frames()[i]) {
            let absent = missing(&step.caption, frame);
            if !absent.is_empty() {
                failures.push(format!(
                    "step {} at {width}×{height} does not show {absent:?}:\n{frame}",
                    i + 1
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
