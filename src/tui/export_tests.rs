//! The lab's exports say what they wrote: `S` names the pressure chart where another scene is
//! shown, `v` names both VTU files.

use super::app::{App, ExportKind, Msg, Scene};
use super::engine::Engine;
use super::export::export_shown;
use super::settle::settle;
use crate::scenario::Scenario;

#[test]
fn exports_say_what_they_wrote() {
    let dir = std::env::temp_dir().join(format!("riplab-export-said-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut app = App::new(Scenario::paper());
    app.settings.level = 0;
    settle(&mut app, &mut Engine::new(Scenario::paper()));
    let said = |app: &App| match export_shown(app, &dir) {
        Msg::Exported(Ok(text)) => text,
        other => panic!("{other:?}"),
    };
    app.export_kind = ExportKind::Svg;
    assert!(!said(&app).contains("pressure chart"), "explore shows it");
    app.scene = Scene::InfSup;
    assert!(said(&app).ends_with(".svg (explore's pressure chart)"));
    app.export_kind = ExportKind::Vtu;
    let text = said(&app);
    let (body, contact) = text.split_once(" and ").expect("two files");
    assert!(
        body.ends_with(".vtu") && contact.ends_with(".contact.vtu"),
        "{text}"
    );
    assert!(std::path::Path::new(contact).exists(), "{contact}");
    std::fs::remove_dir_all(&dir).unwrap();
}
