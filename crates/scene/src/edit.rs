//! Edits of a scene file's text that keep the rest of it as its author wrote it — comments,
//! order, spacing — through `toml_edit`: how the preview's Save view writes a view into the file
//! and how the Python module's `Scene` sets a field. The edited text is a scene to build again
//! ([`crate::parse`]), which checks the new value as it checks any other.

pub use toml_edit::{value, Array, InlineTable, Item, Table, Value};

use toml_edit::{DocumentMut, TableLike};

/// `text` with the fields of the table at the keys `table` (from the root: `["camera"]`,
/// `["views", "top"]`) set to their items, or removed where `None`; the tables on the way are
/// made where missing, implicit: a header is written only for a table with fields of its own
/// (`[views.top]`, not `[views]`). An inline table or dotted keys on the way are edited in place.
pub fn with_fields(text: &str, table: &[&str], fields: Vec<(String, Option<Item>)>) -> Result<String, String> {
    let mut doc: DocumentMut = text.parse().map_err(|e| format!("the scene is not valid TOML: {e}"))?;
    let mut here: &mut dyn TableLike = doc.as_table_mut();
    for (depth, &key) in table.iter().enumerate() {
        let entry = here.entry(key).or_insert_with(|| {
            let mut made = Table::new();
            made.set_implicit(true);
            Item::Table(made)
        });
        let name = table[..=depth].join(".");
        here = entry.as_table_like_mut().ok_or_else(|| format!("the scene's `{name}` is not a table"))?;
    }
    for (key, item) in fields {
        match item {
            Some(item) => {
                here.insert(&key, item);
            }
            None => {
                here.remove(&key);
            }
        }
    }
    Ok(doc.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "# my room\n[camera]   # where I stand\nposition = [0, 0, 7]\nlook_at = [0, 0, 0]\n";

    #[test]
    fn a_field_is_set_and_the_rest_kept() {
        let edited = with_fields(TEXT, &["camera"], vec![("fov".into(), Some(value(30.0)))]).expect("edits");
        assert_eq!(edited, format!("{TEXT}fov = 30.0\n"));
        let back = with_fields(&edited, &["camera"], vec![("fov".into(), None)]).expect("edits");
        assert_eq!(back, TEXT, "removed again");
    }

    #[test]
    fn missing_tables_are_made() {
        let edited = with_fields(TEXT, &["views", "top"], vec![("fov".into(), Some(value(20.0)))]).expect("edits");
        assert!(edited.starts_with(TEXT), "{edited}");
        assert!(edited.ends_with("[views.top]\nfov = 20.0\n"), "no [views] header of its own:\n{edited}");
        let render = with_fields(TEXT, &["render"], vec![("spp".into(), Some(value(4)))]).expect("edits");
        assert!(render.ends_with("[render]\nspp = 4\n"), "{render}");
    }

    #[test]
    fn inline_tables_are_edited_in_place() {
        let text = "camera = { position = [0, 0, 7], look_at = [0, 0, 0] }\n";
        let edited = with_fields(text, &["camera"], vec![("fov".into(), Some(value(30.0)))]).expect("edits");
        assert_eq!(edited, "camera = { position = [0, 0, 7], look_at = [0, 0, 0] , fov = 30.0 }\n");
    }

    #[test]
    fn what_is_not_a_table_is_refused() {
        let error = with_fields("camera = 3\n", &["camera"], vec![]).expect_err("not a table");
        assert_eq!(error, "the scene's `camera` is not a table");
        assert!(with_fields("[camera\n", &["camera"], vec![]).is_err(), "not TOML");
    }
}
