//! CSV in the CLI's formats: a table of records, each column a JSON field of the record (docs/design.md §7).

use serde::Serialize;

/// Where a CSV column's cells come from, in the JSON of its record.
#[derive(Clone, Copy, Debug)]
pub enum Cell {
    /// The field at this JSON pointer (`/errors/p`); empty where it is null or absent.
    Field(&'static str),
    /// The largest number of the array at this pointer.
    Max(&'static str),
    /// The first of these fields that is present and not null.
    First(&'static [&'static str]),
}

/// CSV of `records` with `columns` (header, cell): each cell is read from the record's JSON, so
/// a column names a field the JSON has (the tests check every column against a full record).
pub fn csv_table<T: Serialize>(records: &[T], columns: &[(&str, Cell)]) -> String {
    let mut s = columns.iter().map(|c| c.0).collect::<Vec<_>>().join(",");
    s.push('\n');
    for record in records {
        let json = serde_json::to_value(record).expect("a record is plain data");
        let cells: Vec<String> = columns.iter().map(|&(_, cell)| csv_cell(&json, cell)).collect();
        s.push_str(&cells.join(","));
        s.push('\n');
    }
    s
}

/// One cell of [`csv_table`].
pub(super) fn csv_cell(json: &serde_json::Value, cell: Cell) -> String {
    use serde_json::Value;
    let value = match cell {
        Cell::Field(pointer) => json.pointer(pointer).cloned(),
        Cell::Max(pointer) => json.pointer(pointer).and_then(Value::as_array).map(|a| {
            let max = a.iter().filter_map(Value::as_f64).fold(0.0, f64::max);
            Value::from(max)
        }),
        Cell::First(pointers) => pointers
            .iter()
            .filter_map(|p| json.pointer(p))
            .find(|v| !v.is_null())
            .cloned(),
    };
    match value {
        None | Some(Value::Null) => String::new(),
        Some(Value::String(text)) => csv_field(&text),
        // Floats as Rust prints them (the shortest form that reads back the same).
        Some(Value::Number(n)) => match (n.as_u64(), n.as_i64(), n.as_f64()) {
            (Some(u), _, _) => u.to_string(),
            (None, Some(i), _) => i.to_string(),
            (None, None, Some(f)) => f.to_string(),
            _ => n.to_string(),
        },
        Some(other) => csv_field(&other.to_string()),
    }
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
pub(super) fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}
