//! A step's caption laid out in rows, and the smallest terminal it is laid out in: shared by
//! the view that draws it and the player that scrolls it by those rows; and the checks of a
//! tour's and a step's title and of a caption when the tour is read.

use super::super::view::fmt::wrap_words;
use super::errors::TextError;
use super::{MAX_CAPTION_LINES, MAX_CAPTION_WIDTH};

/// The smallest terminal the tour runs in: the lab's own minimum, its caption below the lab
/// in the rows the lab leaves (scrolling when longer).
pub const MIN_TOUR_SIZE: (u16, u16) = (80, 24);

/// The caption as rows of at most `width` columns: as written when every line fits, else
/// reflowed (a line joins the one before it unless it is indented) and wrapped at words.
pub(super) fn caption_rows(caption: &str, width: u16) -> Vec<String> {
    let width = usize::from(width);
    if caption.lines().all(|l| l.chars().count() <= width) {
        return caption.lines().map(str::to_string).collect();
    }
    let mut paragraphs: Vec<String> = Vec::new();
    for line in caption.lines() {
        match paragraphs.last_mut() {
            Some(last) if !line.starts_with(' ') => {
                last.push(' ');
                last.push_str(line.trim());
            }
            _ => paragraphs.push(line.trim_end().to_string()),
        }
    }
    wrap_words(&paragraphs.join("\n"), width)
}

/// Text on one line of at most `width` characters, not blank.
pub(super) fn one_line(text: &str, width: usize) -> Result<(), TextError> {
    if text.trim().is_empty() {
        return Err(TextError::EmptyLine { width });
    }
    if text.contains('\n') || text.chars().count() > width {
        return Err(TextError::Line { width });
    }
    Ok(())
}

/// A caption of 1 to [`MAX_CAPTION_LINES`] lines of at most [`MAX_CAPTION_WIDTH`] characters.
pub(super) fn caption(text: &str) -> Result<(), TextError> {
    let lines: Vec<&str> = text.trim_matches('\n').lines().collect();
    if text.trim().is_empty() {
        return Err(TextError::EmptyCaption);
    }
    if lines.len() > MAX_CAPTION_LINES {
        return Err(TextError::CaptionLines { lines: lines.len() });
    }
    if let Some((n, line)) = lines
        .iter()
        .enumerate()
        .find(|(_, l)| l.chars().count() > MAX_CAPTION_WIDTH)
    {
        return Err(TextError::CaptionWidth {
            line: n + 1,
            chars: line.chars().count(),
        });
    }
    Ok(())
}
