//! The terminal lab (ratatui + crossterm).
