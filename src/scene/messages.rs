//! The TOML parser's and serde's wording, rewritten for a teacher: what was expected, what was
//! found, and a suggestion where one helps.
//!
//! | serde / toml says | tumble says |
//! |---|---|
//! | `unknown field `gravty`, expected one of …` | unknown key `gravty` (did you mean `gravity`?); valid keys here: … |
//! | `invalid type: string "fast", expected f64` | wrong type: expected a number, found the string "fast" |
//! | `invalid length 2, expected an array of length 3` | wrong length: expected an array of 3 numbers, found 2 elements |
//! | `missing field `body`` | missing table `[body]` |
//! | `missing field `dt`` | this table has no `dt` key, and it is required |
//! | `duplicate key` | TOML syntax error: duplicate key `dt` |

use super::error::did_you_mean;

/// A TOML syntax error's message; `token` is the source text the error points at.
pub fn syntax(message: &str, token: &str) -> String {
    let message = message.trim();
    if message == "duplicate key" && token.trim() == "body" {
        return "TOML syntax error: duplicate key `body`: give one [body], or a [[body]] for each \
                of several bodies, never both"
            .to_string();
    }
    if message == "duplicate key" && !token.trim().is_empty() {
        return format!("TOML syntax error: duplicate key `{}`", token.trim());
    }
    format!("TOML syntax error: {message}")
}

/// A shape error's message (the TOML is valid, but not a scene).
pub fn shape(message: &str) -> String {
    let message = message.trim();
    if let Some(rest) = message.strip_prefix("unknown field `") {
        if let Some(improved) = unknown_key(rest) {
            return improved;
        }
    }
    if let Some(rest) = message.strip_prefix("invalid type: ") {
        if let Some((found, expected)) = rest.split_once(", expected ") {
            return format!(
                "wrong type: expected {}, found {}",
                expected_kind(expected),
                found_kind(found)
            );
        }
    }
    if let Some(rest) = message.strip_prefix("invalid length ") {
        if let Some((found, expected)) = rest.split_once(", expected ") {
            let elements = if found == "1" { "element" } else { "elements" };
            return format!(
                "wrong length: expected {}, found {found} {elements}",
                expected_kind(expected)
            );
        }
    }
    if let Some(rest) = message.strip_prefix("missing field `") {
        let key = rest.trim_end_matches('`');
        return match key {
            "scene" | "body" => {
                format!("missing table `[{key}]`: a scene file needs `title`, [scene] and [body]")
            }
            _ => format!("this table has no `{key}` key, and it is required"),
        };
    }
    message.to_string()
}

/// "`x`, expected one of `a`, `b`" → the unknown-key line with a suggestion.
fn unknown_key(rest: &str) -> Option<String> {
    let (word, expected) = rest.split_once('`')?;
    let valid: Vec<&str> = expected.split('`').skip(1).step_by(2).collect();
    let hint = did_you_mean(word, valid.iter().copied())
        .map(|s| format!(" (did you mean `{s}`?)"))
        .unwrap_or_default();
    Some(format!(
        "unknown key `{word}`{hint}; valid keys here: {}",
        valid.join(", ")
    ))
}

/// serde's name of an expected type, in the scene file's words.
fn expected_kind(expected: &str) -> String {
    match expected {
        "f64" | "f32" => "a number".to_string(),
        "a string" | "a borrowed string" => "a string".to_string(),
        "a sequence" => "an array".to_string(),
        "a boolean" => "true or false".to_string(),
        "struct RawScene" => "the table [scene]".to_string(),
        "struct RawBody" => "the table [body]".to_string(),
        "struct RawDrag" => "a table `{ linear = …, angular = … }`".to_string(),
        "struct RawContact" => {
            "a table `{ response = …, restitution = …, friction = … }`".to_string()
        }
        "struct RawOrientation" => {
            "a table `{ axis = [x, y, z], degrees = a }` or `{ quaternion = [w, x, y, z] }`"
                .to_string()
        }
        "struct RawObstacle" => "an [[obstacle]] table".to_string(),
        "struct RawPage" => "a [[page]] table".to_string(),
        "struct RawCloth" => "a [[cloth]] table".to_string(),
        "struct RawJoint" => "a [[joint]] table".to_string(),
        "struct RawSpring" => "a [[spring]] table".to_string(),
        "struct RawMotor" => "a table `{ speed = …, max_force = … }` (slider) or `{ speed = …, \
                               max_torque = … }` (hinge)"
            .to_string(),
        "struct RawPredict" => "a table `{ quantity = \"cube.y\", at = 1.0 }`".to_string(),
        "struct RawAttach" => {
            "a table `{ particle = [i, j], body = \"name\" }` or `{ edge = \"-x\", body = \"name\" }`"
                .to_string()
        }
        "i64" | "u64" | "usize" => "an integer".to_string(),
        other => match other.strip_prefix("an array of length ") {
            Some(n) => format!("an array of {n} numbers"),
            // No internal type's name reaches a user: any other table is "a table".
            None if other.starts_with("struct ") => "a table".to_string(),
            None => other.to_string(),
        },
    }
}

/// serde's description of a found value, e.g. `string "fast"` → `the string "fast"`.
fn found_kind(found: &str) -> String {
    let unquote = |s: &str| s.trim_matches('`').to_string();
    if let Some(value) = found.strip_prefix("integer ") {
        format!("the integer {}", unquote(value))
    } else if let Some(value) = found.strip_prefix("floating point ") {
        format!("the number {}", unquote(value))
    } else if let Some(value) = found.strip_prefix("boolean ") {
        format!("the boolean {}", unquote(value))
    } else if let Some(value) = found.strip_prefix("string ") {
        format!("the string {value}")
    } else if found == "sequence" {
        "an array".to_string()
    } else if found == "map" {
        "a table".to_string()
    } else {
        found.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serde_wording_becomes_expected_and_found() {
        assert_eq!(
            shape("invalid type: string \"fast\", expected f64"),
            "wrong type: expected a number, found the string \"fast\""
        );
        assert_eq!(
            shape("invalid length 2, expected an array of length 3"),
            "wrong length: expected an array of 3 numbers, found 2 elements"
        );
        assert_eq!(
            shape("invalid type: floating point `0.3`, expected struct RawDrag"),
            "wrong type: expected a table `{ linear = …, angular = … }`, found the number 0.3"
        );
        assert_eq!(
            shape("missing field `dt`"),
            "this table has no `dt` key, and it is required"
        );
        assert_eq!(
            syntax("duplicate key", "dt"),
            "TOML syntax error: duplicate key `dt`"
        );
    }
}
