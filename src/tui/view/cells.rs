//! Where ratatui's canvas draws a value: the cell of a value on an axis and the dots per cell
//! of a marker (shared by the charts, their axes and the cursor).

use ratatui::symbols::Marker;

/// Dots per cell of a marker (columns, rows), as ratatui's canvas grids have them.
pub fn dots_per_cell(marker: Marker) -> (u16, u16) {
    match marker {
        Marker::Braille => (2, 4),
        Marker::HalfBlock => (1, 2),
        Marker::Quadrant => (2, 2),
        Marker::Sextant => (2, 3),
        Marker::Octant => (2, 4),
        _ => (1, 1),
    }
}

/// The cell offset (0-based, from the low end) at which ratatui's canvas draws `value` on an
/// axis of `cells` cells over `bounds`, `per` dots per cell: the dot is
/// round(t·(dots − 1)) for t = (value − lo)/(hi − lo), its cell that dot / per.
pub fn cell_of(value: f64, bounds: [f64; 2], cells: u16, per: u16) -> Option<u16> {
    let (lo, hi) = (bounds[0], bounds[1]);
    let ordered = hi > lo;
    if !ordered || !value.is_finite() || value < lo || value > hi || cells == 0 {
        return None;
    }
    let dots = f64::from(cells) * f64::from(per);
    let dot = ((value - lo) / (hi - lo) * (dots - 1.0)).round() as u16;
    Some(dot / per)
}
