//! The contact solve of two bodies across their interface (docs/design.md §12).
