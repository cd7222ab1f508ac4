//! Which keys each kind of table takes: one place for the shapes of a body, the types of a
//! joint (a cloth's `attach` entry takes `particle` or `edge`, and `body`: `cloth.rs`). A key the TOML parser knows but this kind
//! does not take (`size` on a sphere, `axis` on a ball joint) is an error at that key, naming
//! it, the kinds that do take it, a "did you mean" among this kind's keys, and the valid keys:
//!
//! ```text
//! `size` does not apply to a sphere body (it is a key of box); valid keys of a sphere body:
//!     name, shape, fixed, mass, …, radius
//! `anchors` does not apply to a ball joint (did you mean `anchor`?; it is a key of
//!     distance); valid keys of a ball joint: name, type, bodies, anchor
//! ```
//!
//! A new shape or key is one line of a table below (and its field in `raw.rs`); the joint
//! kinds declare their `type` word and keys in their own files (`physics::joints::written`,
//! `JointKind::WRITTEN`).

use super::error::did_you_mean;
use crate::physics::joints::JointKind;
use std::ops::Range;

/// A kind of table (a shape, a joint type) and the keys it takes beside the common ones: its
/// word (`name`) and `keys`.
pub use crate::physics::joints::written::Written as Kind;

/// A family of kinds: the keys every kind takes, and each kind's own.
#[derive(Debug)]
pub struct Family {
    /// "body", "joint": how the table is called in messages.
    pub table: &'static str,
    /// The key that names the kind (`shape`, `type`).
    pub selector: &'static str,
    pub common: &'static [&'static str],
    pub kinds: &'static [Kind],
}

/// A body's shapes.
pub const SHAPES: Family = Family {
    table: "body",
    selector: "shape",
    common: &[
        "name",
        "shape",
        "fixed",
        "mass",
        "inertia",
        "position",
        "orientation",
        "velocity",
        "angular_velocity",
        "angular_velocity_body",
    ],
    kinds: &[
        Kind {
            name: "box",
            keys: &["size"],
        },
        Kind {
            name: "points",
            keys: &["points", "masses"],
        },
        Kind {
            name: "mesh",
            keys: &["file"],
        },
        Kind {
            name: "sphere",
            keys: &["radius"],
        },
        Kind {
            name: "capsule",
            keys: &["radius", "length"],
        },
        Kind {
            name: "cylinder",
            keys: &["radius", "length"],
        },
    ],
};

/// A joint's types, as each kind's file writes it (`JointKind::WRITTEN`).
pub const JOINTS: Family = Family {
    table: "joint",
    selector: "type",
    common: &["name", "type", "bodies"],
    kinds: &JointKind::WRITTEN,
};

impl Family {
    /// The kind named `word`, or the error for an unknown one: "unknown shape `sphre` (did
    /// you mean `sphere`?); valid shapes: box, …".
    pub fn kind(&self, word: &str) -> Result<&Kind, String> {
        self.kinds.iter().find(|k| k.name == word).ok_or_else(|| {
            let names = self.names();
            let hint = did_you_mean(word, names.iter().copied())
                .map(|s| format!(" (did you mean `{s}`?)"))
                .unwrap_or_default();
            let (what, plural) = match self.selector {
                "shape" => ("shape", "shapes"),
                _ => ("joint type", "types"),
            };
            format!(
                "unknown {what} `{word}`{hint}; valid {plural}: {}",
                names.join(", ")
            )
        })
    }

    /// Every kind's name, in table order.
    pub fn names(&self) -> Vec<&'static str> {
        self.kinds.iter().map(|k| k.name).collect()
    }

    /// The first key of `present` that `kind` does not take: its span and the message.
    pub fn misplaced(
        &self,
        kind: &Kind,
        present: &[(&'static str, Range<usize>)],
    ) -> Option<(Range<usize>, String)> {
        let (key, span) = present
            .iter()
            .find(|(key, _)| !self.common.contains(key) && !kind.keys.contains(key))?;
        let mut notes = Vec::new();
        if let Some(close) = did_you_mean(key, kind.keys.iter().copied()) {
            notes.push(format!("did you mean `{close}`?"));
        }
        let owners: Vec<&str> = self
            .kinds
            .iter()
            .filter(|k| k.keys.contains(key))
            .map(|k| k.name)
            .collect();
        if !owners.is_empty() {
            notes.push(format!("it is a key of {}", owners.join(", ")));
        }
        let notes = if notes.is_empty() {
            String::new()
        } else {
            format!(" ({})", notes.join("; "))
        };
        let valid: Vec<&str> = self.common.iter().chain(kind.keys).copied().collect();
        Some((
            span.clone(),
            format!(
                "`{key}` does not apply to a {kind} {table}{notes}; valid keys of a {kind} \
                 {table}: {valid}",
                kind = kind.name,
                table = self.table,
                valid = valid.join(", ")
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_key_of_another_kind_is_named_with_its_owners_and_the_valid_keys() {
        let sphere = SHAPES.kind("sphere").unwrap();
        let (span, message) = SHAPES.misplaced(sphere, &[("size", 4..8)]).unwrap();
        assert_eq!(span, 4..8);
        assert!(
            message.starts_with("`size` does not apply to a sphere body (it is a key of box)"),
            "{message}"
        );
        assert!(
            message.ends_with("angular_velocity_body, radius"),
            "{message}"
        );
        let ball = JOINTS.kind("ball").unwrap();
        let (_, message) = JOINTS.misplaced(ball, &[("anchors", 0..1)]).unwrap();
        assert!(
            message.contains("(did you mean `anchor`?; it is a key of distance)"),
            "{message}"
        );
        assert!(SHAPES.misplaced(sphere, &[("radius", 0..1)]).is_none());
        assert!(SHAPES
            .kind("sphre")
            .unwrap_err()
            .contains("(did you mean `sphere`?)"));
    }

    #[test]
    fn the_tables_name_every_joint_kind_and_no_other() {
        let mut table = JOINTS.names();
        let mut model: Vec<&str> = JointKind::ALL.iter().map(|k| k.name()).collect();
        table.sort_unstable();
        model.sort_unstable();
        assert_eq!(table, model);
    }

    #[test]
    fn every_kind_is_named_once_and_its_keys_are_not_common() {
        for family in [&SHAPES, &JOINTS] {
            let names = family.names();
            for (i, name) in names.iter().enumerate() {
                assert!(!names[..i].contains(name), "{name} twice");
            }
            for kind in family.kinds {
                for key in kind.keys {
                    assert!(!family.common.contains(key), "{key}");
                }
            }
        }
    }
}
