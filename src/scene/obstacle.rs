//! An `[[obstacle]]` table read through the obstacle kinds' own words
//! (`physics::collision::obstacle::written`): this file knows no kind. It checks what every kind
//! shares — the `type` word is a kind's, no key of another kind is written, every required key
//! is there — then hands the kind a lookup of its keys ([`Keys`]) that pins each error to
//! where the key was written (file:line:column).

use super::error::did_you_mean;
use super::raw::{RawObstacle, RawValue};
use super::{LoadError, Validator};
use crate::physics::collision::obstacle::{written, Keys};
use crate::physics::Obstacle;
use nalgebra::{UnitQuaternion, Vector3};
use std::ops::Range;
use toml::Spanned;

impl Validator<'_> {
    pub(super) fn obstacle(&self, raw: &Spanned<RawObstacle>) -> Result<Obstacle, LoadError> {
        let o = raw.get_ref();
        let span = raw.span();
        let kind = o.kind.get_ref().as_str();
        let kinds = written::written();
        let Some(&(_, how)) = kinds.iter().find(|(word, _)| *word == kind) else {
            let names: Vec<&str> = kinds.iter().map(|(word, _)| *word).collect();
            let hint = did_you_mean(kind, names.iter().copied())
                .map(|s| format!(" (did you mean `{s}`?)"))
                .unwrap_or_default();
            return Err(self.error(
                o.kind.span(),
                format!(
                    "unknown obstacle type `{kind}`{hint}; valid types: {}",
                    names.join(", ")
                ),
            ));
        };
        let allowed: Vec<&str> = how.keys.iter().map(|k| k.name).collect();
        for key in written::all_keys() {
            if let (Some(value), false) = (o.value(key.name), allowed.contains(&key.name)) {
                return Err(self.error(
                    value.span(),
                    format!(
                        "`{}` does not apply to a {kind} obstacle; valid keys: type, {}",
                        key.name,
                        allowed.join(", ")
                    ),
                ));
            }
        }
        let keys = ObstacleKeys {
            v: self,
            raw: o,
            kind,
            span,
        };
        for key in how.keys.iter().filter(|k| k.required) {
            if o.value(key.name).is_none() {
                return Err(keys.missing(key.name));
            }
        }
        written::build(kind, &keys).unwrap_or_else(|| Err(keys.missing("type")))
    }
}

/// The keys of one `[[obstacle]]` table, as its kind reads them.
struct ObstacleKeys<'a> {
    v: &'a Validator<'a>,
    raw: &'a RawObstacle,
    kind: &'a str,
    /// The table's span: where a missing key is blamed.
    span: Range<usize>,
}

impl ObstacleKeys<'_> {
    fn missing(&self, key: &str) -> LoadError {
        self.v.error(
            self.span.clone(),
            format!("a {} obstacle needs `{key}`", self.kind),
        )
    }

    /// A value of another sort than the kind reads (two kinds declaring one key differently).
    fn sort(&self, key: &str, value: &RawValue, sort: &str) -> LoadError {
        self.v
            .error(value.span(), format!("`{key}` must be {sort}"))
    }
}

impl Keys for ObstacleKeys<'_> {
    type Error = LoadError;

    fn finite(&self, key: &str) -> Result<f64, LoadError> {
        match self.raw.value(key) {
            Some(RawValue::Number(v)) => self.v.finite(v, key),
            Some(other) => Err(self.sort(key, other, "a number")),
            None => Err(self.missing(key)),
        }
    }

    fn positive(&self, key: &str) -> Result<f64, LoadError> {
        match self.raw.value(key) {
            Some(RawValue::Number(v)) => self.v.positive(v, key),
            Some(other) => Err(self.sort(key, other, "a number")),
            None => Err(self.missing(key)),
        }
    }

    fn vector(&self, key: &str) -> Result<Vector3<f64>, LoadError> {
        match self.raw.value(key) {
            Some(RawValue::Vector(v)) => self.v.vector(v, key),
            Some(other) => Err(self.sort(key, other, "an array of 3 numbers")),
            None => Err(self.missing(key)),
        }
    }

    fn rotation(&self, key: &str) -> Result<Option<UnitQuaternion<f64>>, LoadError> {
        match self.raw.value(key) {
            Some(RawValue::Rotation(r)) => self.v.orientation(r).map(Some),
            Some(other) => Err(self.sort(key, other, "an orientation table")),
            None => Ok(None),
        }
    }

    fn wrong(&self, key: &str, message: String) -> LoadError {
        match self.raw.value(key) {
            Some(value) => self.v.error(value.span(), message),
            None => self.v.error(self.span.clone(), message),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::physics::collision::obstacle::written;

    /// Every obstacle type and key a kind declares (in its own file, not in `raw.rs`) appears in
    /// `docs/lesson-format.md` as `` `word` `` or `` "word" ``.
    #[test]
    fn every_obstacle_type_and_key_is_documented() {
        let docs = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/lesson-format.md"),
        )
        .unwrap();
        let kinds = written::written();
        let words = kinds.iter().map(|(word, _)| *word);
        let keys = written::all_keys().into_iter().map(|k| k.name);
        let missing: Vec<&str> = words
            .chain(keys)
            .filter(|w| !docs.contains(&format!("`{w}`")) && !docs.contains(&format!("\"{w}\"")))
            .collect();
        assert!(
            missing.is_empty(),
            "docs/lesson-format.md does not mention {missing:?}"
        );
    }
}
