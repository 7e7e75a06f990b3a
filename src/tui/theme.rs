//! Colours and emphasis: the 16 ANSI colours, or a monochrome theme built on modifiers
//! (REVERSED, BOLD, UNDERLINED) when NO_COLOR is set, so that selections stay visible.

use ratatui::style::{Color, Modifier, Style};

/// The look of the app.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Theme {
    /// False: monochrome, emphasis by modifiers only.
    pub color: bool,
}

impl Theme {
    /// Colour unless `no_color` or the environment's NO_COLOR (any non-empty value) says not.
    pub fn new(no_color: bool) -> Self {
        let env = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
        Theme {
            color: !(no_color || env),
        }
    }

    /// A colour for canvas shapes (which take no modifiers).
    pub fn ink(self, c: Color) -> Color {
        if self.color { c } else { Color::Reset }
    }

    fn fg(self, c: Color) -> Style {
        Style::new().fg(self.ink(c))
    }

    /// Raw pressure p (a dotted line).
    pub fn raw_color(self) -> Color {
        self.ink(Color::Yellow)
    }
    /// Smoothed pressure p̄ (a solid line).
    pub fn smooth_color(self) -> Color {
        self.ink(Color::Cyan)
    }
    /// The Hertz profile.
    pub fn hertz_color(self) -> Color {
        self.ink(Color::Magenta)
    }
    /// The gap overlay and other secondary lines.
    pub fn faint_color(self) -> Color {
        self.ink(Color::DarkGray)
    }
    /// Secondary text.
    pub fn faint(self) -> Style {
        self.fg(Color::DarkGray)
    }
    /// Axes and frames.
    pub fn axis(self) -> Style {
        self.fg(Color::Gray)
    }
    /// The obstacle.
    pub fn obstacle(self) -> Color {
        self.ink(Color::Red)
    }
    /// The deformed mesh.
    pub fn mesh(self) -> Color {
        self.ink(Color::Blue)
    }
    /// Titles and the scenario name.
    pub fn title(self) -> Style {
        Style::new().add_modifier(Modifier::BOLD)
    }
    /// The selected tab or row.
    pub fn selected(self) -> Style {
        if self.color {
            Style::new()
                .fg(Color::Black)
                .bg(Color::Cyan)
                .add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::REVERSED | Modifier::BOLD)
        }
    }
    /// Good news (converged, stable).
    pub fn good(self) -> Style {
        if self.color {
            self.fg(Color::Green)
        } else {
            Style::new().add_modifier(Modifier::BOLD)
        }
    }
    /// Bad news (not converged, unstable).
    pub fn bad(self) -> Style {
        if self.color {
            self.fg(Color::LightRed).add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::BOLD | Modifier::UNDERLINED)
        }
    }
    /// Work in progress.
    pub fn busy(self) -> Style {
        self.fg(Color::Yellow)
    }
    /// Key names in the help and the status line.
    pub fn key(self) -> Style {
        self.fg(Color::Yellow).add_modifier(Modifier::BOLD)
    }
    /// The error banner.
    pub fn banner(self) -> Style {
        if self.color {
            Style::new()
                .fg(Color::White)
                .bg(Color::Red)
                .add_modifier(Modifier::BOLD)
        } else {
            Style::new().add_modifier(Modifier::REVERSED | Modifier::BOLD)
        }
    }
}
