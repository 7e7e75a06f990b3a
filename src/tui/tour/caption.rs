//! A step's caption laid out in rows, and the smallest terminal it is laid out in: shared by
//! the view that draws it and the player that scrolls it by those rows.

use super::super::view::fmt::wrap_words;

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
