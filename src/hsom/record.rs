//! `#[serde(with = "strings")]` for a `Vec<String>` of names read from a model file (columns,
//! labels): each copied from the file's bytes where the binary form borrows them
//! ([`crate::config::Text`]), so that a length a file claims sizes nothing before the bytes
//! are there.

pub(crate) mod strings {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    use crate::config::Text;

    pub(crate) fn serialize<S: Serializer>(v: &[String], s: S) -> Result<S::Ok, S::Error> {
        v.serialize(s)
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<String>, D::Error> {
        Ok(Vec::<Text>::deserialize(d)?
            .into_iter()
            .map(|t| t.0)
            .collect())
    }
}
