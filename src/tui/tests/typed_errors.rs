//! The lab's errors are typed and keep their sources; their
//! messages are the ones users saw before (the CLI tests check the texts).

use std::error::Error as _;

use riplab::scenario::Scenario;
use riplab::tui::{RenderError, SizeError, parse_size, render_to_string};

#[test]
fn sizes_and_render_requests_fail_with_their_variant() {
    assert_eq!(
        parse_size("eighty"),
        Err(SizeError::NotASize {
            text: "eighty".into()
        })
    );
    assert_eq!(
        parse_size("79x24"),
        Err(SizeError::OutOfRange {
            width: 79,
            height: 24
        })
    );
    let render = |scene: &str, w, level, epsilon| {
        render_to_string(&Scenario::paper(), scene, w, 24, level, None, None, epsilon).unwrap_err()
    };
    assert!(matches!(
        render("plot", 80, None, None),
        RenderError::UnknownScene { .. }
    ));
    assert!(matches!(
        render("mesh", 79, None, None),
        RenderError::Size(SizeError::OutOfRange { .. })
    ));
    assert_eq!(render("mesh", 80, Some(9), None), RenderError::Level { level: 9 });
    let e = render("mesh", 80, Some(0), Some(-1.0));
    assert!(matches!(e, RenderError::Epsilon(_)), "{e:?}");
    assert!(e.source().is_some(), "the check's error is its source");
    assert!(e.to_string().starts_with("ε: "), "{e}");
}
