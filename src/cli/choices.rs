//! The command line's names for the library's choices (docs/design.md §8): clap's
//! `ValueEnum` on mirrors of the core's enums ([`Element`], [`Rule`], [`Format`] and the lab's
//! [`MarkerChoice`]), each mapped onto its enum by [`choice`], so that the core derives
//! nothing of clap and builds without it.

use clap::ValueEnum;
use clap::builder::{EnumValueParser, TypedValueParser};

use crate::contact::Rule;
use crate::mesh::Element;
use crate::output::Format;
use crate::tui::MarkerChoice;

/// clap's parser of the names of `A`, giving the library's `T` (its possible values, with
/// their help, are `A`'s).
pub fn choice<A, T>() -> impl TypedValueParser<Value = T>
where
    A: ValueEnum + Clone + Send + Sync + 'static,
    T: From<A> + Clone + Send + Sync + 'static,
{
    EnumValueParser::<A>::new().map(T::from)
}

/// `--element`: [`Element`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ElementName {
    /// Bilinear 4-node quadrilateral, the paper's element.
    Q1,
    /// Biquadratic 9-node quadrilateral (needed for the paper's M4).
    Q2,
    /// Linear 3-node triangle, two per cell (named in the paper's Theorem 2).
    P1,
}

impl From<ElementName> for Element {
    fn from(name: ElementName) -> Element {
        match name {
            ElementName::Q1 => Element::Q1,
            ElementName::Q2 => Element::Q2,
            ElementName::P1 => Element::P1,
        }
    }
}

/// `--rule`: [`Rule`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum RuleName {
    /// One-point Gauss: piecewise-constant pressure (M1).
    Gauss1,
    /// Two-point Gauss: discontinuous linear pressure (M2).
    Gauss2,
    /// Trapezoid: continuous linear pressure (M3).
    Trapezoid,
    /// Simpson: continuous quadratic pressure (M4 with Q2).
    Simpson,
}

impl From<RuleName> for Rule {
    fn from(name: RuleName) -> Rule {
        match name {
            RuleName::Gauss1 => Rule::Gauss1,
            RuleName::Gauss2 => Rule::Gauss2,
            RuleName::Trapezoid => Rule::Trapezoid,
            RuleName::Simpson => Rule::Simpson,
        }
    }
}

/// `--format`: [`Format`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FormatName {
    /// The human table.
    Table,
    /// CSV: a header line, then a row per record.
    Csv,
    /// JSON (docs/design.md §7), pretty-printed.
    Json,
}

impl From<FormatName> for Format {
    fn from(name: FormatName) -> Format {
        match name {
            FormatName::Table => Format::Table,
            FormatName::Csv => Format::Csv,
            FormatName::Json => Format::Json,
        }
    }
}

/// `--marker`: [`MarkerChoice`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MarkerName {
    /// Unicode braille: 2×4 dots per cell (the sharpest).
    Braille,
    /// Half blocks: 1×2 per cell, for fonts without braille.
    #[value(name = "halfblock")]
    HalfBlock,
    /// One dot per cell.
    Dot,
}

impl From<MarkerName> for MarkerChoice {
    fn from(name: MarkerName) -> MarkerChoice {
        match name {
            MarkerName::Braille => MarkerChoice::Braille,
            MarkerName::HalfBlock => MarkerChoice::HalfBlock,
            MarkerName::Dot => MarkerChoice::Dot,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names of `A` on the command line, with the value each gives.
    fn names<A: ValueEnum, T: From<A>>() -> Vec<(String, T)> {
        A::value_variants()
            .iter()
            .map(|a| {
                let name = a.to_possible_value().unwrap().get_name().to_string();
                (name, T::from(a.clone()))
            })
            .collect()
    }

    /// Every element and rule has its command-line name the name the library gives it in
    /// scenario files and outputs, and every one of the library's values is reachable.
    #[test]
    fn the_command_line_names_every_value_as_the_library_does() {
        let elements = names::<ElementName, Element>();
        assert_eq!(elements.iter().map(|(_, e)| *e).collect::<Vec<_>>(), Element::ALL);
        assert!(elements.iter().all(|(name, e)| name == e.name()), "{elements:?}");
        let rules = names::<RuleName, Rule>();
        assert_eq!(rules.iter().map(|(_, r)| *r).collect::<Vec<_>>(), Rule::ALL);
        assert!(rules.iter().all(|(name, r)| name == r.name()), "{rules:?}");
        assert_eq!(
            names::<FormatName, Format>(),
            [
                ("table".into(), Format::Table),
                ("csv".into(), Format::Csv),
                ("json".into(), Format::Json)
            ]
        );
        assert_eq!(
            names::<MarkerName, MarkerChoice>(),
            [
                ("braille".into(), MarkerChoice::Braille),
                ("halfblock".into(), MarkerChoice::HalfBlock),
                ("dot".into(), MarkerChoice::Dot)
            ]
        );
    }
}

/// `--contact`: the discretisation of the constraint across two bodies' interface
/// ([`crate::contact::interface::InterfaceMethod`]; `rip` takes the rule of `--rule`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ContactName {
    /// Node-to-segment, one pass: each slave node onto the master's segments.
    Nts,
    /// Node-to-segment, two pass: the slave's nodes onto the master and the master's onto the
    /// slave.
    Nts2,
    /// Mortar segment-to-segment, the slave's trace space as multipliers.
    Mortar,
    /// Mortar segment-to-segment, the biorthogonal (dual) basis as multipliers.
    MortarDual,
    /// The reduced-integration penalty: the rule's points (--rule) on the slave's edges.
    Rip,
}
