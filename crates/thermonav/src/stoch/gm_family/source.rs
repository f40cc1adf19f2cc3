//! [`GaussMarkovSource`], the name of one registered family as callers, files and the command
//! line hold it, and [`GaussMarkovModels`], a channel's estimates keyed by family.

use super::FAMILIES;
use super::family::{FitInputs, GaussMarkovEstimate, GaussMarkovFamily};
use super::{acf_fit, ar_based, gmwm, irregular_ml};
use serde::de::{self, IgnoredAny, MapAccess, SeqAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::sync::LazyLock;

/// Which of the Gauss-Markov families to use (the default: the exact likelihood on the
/// irregular timestamps, see DESIGN.md). Written in files by its family's
/// name (`irregular_ml`, [`super::FamilyNames`]).
#[derive(Clone, Copy)]
pub struct GaussMarkovSource(&'static dyn GaussMarkovFamily);

impl GaussMarkovSource {
    /// AR(1)-based (the paper's).
    pub const AR_BASED: Self = Self(&ar_based::ArBased);
    /// Exact maximum likelihood on the irregular timestamps.
    pub const IRREGULAR_ML: Self = Self(&irregular_ml::IrregularMl);
    /// Fit to the autocorrelation.
    pub const ACF_FIT: Self = Self(&acf_fit::AcfFit);
    /// The bias state of the GMWM composite (and its white noise, see
    /// [`crate::stoch::gmwm::map_to_filter_states`]).
    pub const GMWM: Self = Self(&gmwm::Gmwm);

    /// The family itself.
    pub fn family(self) -> &'static dyn GaussMarkovFamily {
        self.0
    }

    /// Its name in files ([`super::FamilyNames`]).
    pub fn name(self) -> &'static str {
        self.0.names().name
    }

    /// Its value on the command line ([`super::FamilyNames`]).
    pub fn cli_name(self) -> &'static str {
        self.0.names().cli_name
    }

    /// One line on it for the command line's help ([`super::FamilyNames`]).
    pub fn help(self) -> &'static str {
        self.0.names().help
    }

    /// Its legend name in figures ([`super::FamilyNames`]).
    pub fn label(self) -> &'static str {
        self.0.names().label
    }

    /// Whether every bank has it ([`GaussMarkovFamily::when_absent`] is `None`).
    pub fn always_fitted(self) -> bool {
        self.0.when_absent().is_none()
    }

    /// Whether its model may have σ = 0 ([`GaussMarkovFamily::sigma_may_be_zero`]).
    pub fn sigma_may_be_zero(self) -> bool {
        self.0.sigma_may_be_zero()
    }

    /// Every registered family, in the bank's order.
    pub fn all() -> impl Iterator<Item = Self> {
        FAMILIES.iter().map(|&f| Self(f))
    }

    /// Every registered family as the command line and Python list them: the default first,
    /// then the others in the bank's order.
    pub fn in_listing_order() -> impl Iterator<Item = Self> {
        let default = Self::default();
        std::iter::once(default).chain(Self::all().filter(move |&s| s != default))
    }

    /// The family written `name` in files.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::all().find(|s| s.name() == name)
    }

    /// Its place in [`FAMILIES`].
    fn index(self) -> usize {
        FAMILIES
            .iter()
            .position(|f| f.names().name == self.name())
            .unwrap_or(0)
    }
}

impl Default for GaussMarkovSource {
    fn default() -> Self {
        Self::IRREGULAR_ML
    }
}

impl PartialEq for GaussMarkovSource {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

impl Eq for GaussMarkovSource {}

/// The name in CamelCase (`IrregularMl`), as the enum this type replaced printed it (the
/// tournament's heading prints it so).
impl fmt::Debug for GaussMarkovSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for word in self.name().split('_') {
            let mut letters = word.chars();
            if let Some(first) = letters.next() {
                write!(f, "{}{}", first.to_ascii_uppercase(), letters.as_str())?;
            }
        }
        Ok(())
    }
}

/// The registered names, in the bank's order (serde's lists of what was expected).
static NAMES: LazyLock<Vec<&'static str>> = LazyLock::new(|| {
    GaussMarkovSource::all()
        .map(GaussMarkovSource::name)
        .collect()
});

impl Serialize for GaussMarkovSource {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for GaussMarkovSource {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        Self::from_name(&name).ok_or_else(|| de::Error::unknown_variant(&name, &NAMES))
    }
}

/// The Gauss-Markov models of one channel: at most one estimate per family, written as an
/// object keyed by the families' names in the order of [`FAMILIES`]. A family that every
/// bank has ([`GaussMarkovSource::always_fitted`]) must be in a file read.
#[derive(Debug, Clone, PartialEq)]
pub struct GaussMarkovModels {
    /// Per family, in the order of [`FAMILIES`].
    estimates: Vec<Option<GaussMarkovEstimate>>,
}

/// What [`GaussMarkovModels::get`] gives for a family the models lack.
static ABSENT: LazyLock<Vec<GaussMarkovEstimate>> = LazyLock::new(|| {
    GaussMarkovSource::all()
        .map(|s| GaussMarkovEstimate::NoEquivalent {
            reason: s.family().when_absent().map_or_else(
                || format!("the bank has no {} model", s.name()),
                str::to_string,
            ),
        })
        .collect()
});

impl Default for GaussMarkovModels {
    fn default() -> Self {
        Self {
            estimates: vec![None; FAMILIES.len()],
        }
    }
}

impl GaussMarkovModels {
    /// Every family fitted to one channel's inputs (those fitted, [`GaussMarkovFamily::fit`]).
    ///
    /// # Errors
    /// The first family's reason the channel cannot be modelled.
    pub fn fit(inputs: &FitInputs<'_>) -> Result<Self, String> {
        let mut models = Self::default();
        for source in GaussMarkovSource::all() {
            models.estimates[source.index()] = source.family().fit(inputs)?;
        }
        Ok(models)
    }

    /// The models with `estimate` for `source` (replacing any).
    #[must_use]
    pub fn with(mut self, source: GaussMarkovSource, estimate: GaussMarkovEstimate) -> Self {
        self.estimates[source.index()] = Some(estimate);
        self
    }

    /// The estimate of one source; for a family the models lack, its reason
    /// ([`GaussMarkovFamily::when_absent`]) as a [`GaussMarkovEstimate::NoEquivalent`].
    pub fn get(&self, source: GaussMarkovSource) -> &GaussMarkovEstimate {
        let index = source.index();
        self.estimates[index].as_ref().unwrap_or(&ABSENT[index])
    }

    /// The estimate of one source, when the models have it.
    pub fn estimate(&self, source: GaussMarkovSource) -> Option<&GaussMarkovEstimate> {
        self.estimates[source.index()].as_ref()
    }

    /// The estimates present, in the order of [`FAMILIES`].
    pub fn iter(&self) -> impl Iterator<Item = (GaussMarkovSource, &GaussMarkovEstimate)> {
        GaussMarkovSource::all().filter_map(|s| Some((s, self.estimate(s)?)))
    }
}

impl Serialize for GaussMarkovModels {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.iter().count()))?;
        for (source, estimate) in self.iter() {
            map.serialize_entry(source.name(), estimate)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for GaussMarkovModels {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_struct("GaussMarkovModels", &NAMES, ModelsVisitor)
    }
}

/// Reads [`GaussMarkovModels`] as serde reads a struct with one field per family (the
/// optional families' fields `Option`s with a default): unknown keys ignored, a repeated or
/// missing one refused.
struct ModelsVisitor;

impl<'de> Visitor<'de> for ModelsVisitor {
    type Value = GaussMarkovModels;

    fn expecting(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str("struct GaussMarkovModels")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut models = GaussMarkovModels::default();
        let mut seen = vec![false; FAMILIES.len()];
        while let Some(key) = map.next_key::<String>()? {
            let Some(source) = GaussMarkovSource::from_name(&key) else {
                map.next_value::<IgnoredAny>()?;
                continue;
            };
            let index = source.index();
            if std::mem::replace(&mut seen[index], true) {
                return Err(de::Error::duplicate_field(source.name()));
            }
            models.estimates[index] = if source.always_fitted() {
                Some(map.next_value::<GaussMarkovEstimate>()?)
            } else {
                map.next_value::<Option<GaussMarkovEstimate>>()?
            };
        }
        match GaussMarkovSource::all().find(|s| s.always_fitted() && !seen[s.index()]) {
            Some(missing) => Err(de::Error::missing_field(missing.name())),
            None => Ok(models),
        }
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut models = GaussMarkovModels::default();
        for (index, source) in GaussMarkovSource::all().enumerate() {
            models.estimates[index] = if source.always_fitted() {
                let estimate = seq.next_element::<GaussMarkovEstimate>()?;
                Some(estimate.ok_or_else(|| de::Error::invalid_length(index, &self))?)
            } else {
                seq.next_element::<Option<GaussMarkovEstimate>>()?.flatten()
            };
        }
        Ok(models)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(tc: f64) -> GaussMarkovEstimate {
        GaussMarkovEstimate::Model {
            correlation_time_s: tc,
            sigma: 0.5,
            ci95_correlation_time_s: [Some(1.0), None],
        }
    }

    #[test]
    fn every_family_has_its_own_names_and_is_found_by_them() {
        let all: Vec<GaussMarkovSource> = GaussMarkovSource::all().collect();
        assert_eq!(all.len(), FAMILIES.len());
        for (i, a) in all.iter().enumerate() {
            assert_eq!(GaussMarkovSource::from_name(a.name()), Some(*a));
            assert_eq!(a.index(), i);
            for b in &all[i + 1..] {
                assert!(a.name() != b.name() && a.cli_name() != b.cli_name());
                assert!(a.label() != b.label() && a != b);
            }
        }
        assert_eq!(GaussMarkovSource::from_name("irregular-ml"), None);
    }

    #[test]
    fn the_command_line_lists_the_default_first() {
        let listed: Vec<&str> = GaussMarkovSource::in_listing_order()
            .map(GaussMarkovSource::cli_name)
            .collect();
        assert_eq!(listed, ["irregular-ml", "ar-based", "acf-fit", "gmwm"]);
        assert_eq!(
            GaussMarkovSource::default(),
            GaussMarkovSource::IRREGULAR_ML
        );
    }

    #[test]
    fn a_source_is_written_by_its_name_and_debug_keeps_the_old_variant_names() {
        let text = serde_json::to_string(&GaussMarkovSource::ACF_FIT).unwrap();
        assert_eq!(text, "\"acf_fit\"");
        let back: GaussMarkovSource = serde_json::from_str(&text).unwrap();
        assert_eq!(back, GaussMarkovSource::ACF_FIT);
        let unknown = serde_json::from_str::<GaussMarkovSource>("\"ml\"").unwrap_err();
        assert!(
            unknown.to_string().starts_with(
                "unknown variant `ml`, expected one of `ar_based`, `irregular_ml`, `acf_fit`, `gmwm`"
            ),
            "{unknown}"
        );
        assert_eq!(
            format!("{:?}", GaussMarkovSource::IRREGULAR_ML),
            "IrregularMl"
        );
        assert_eq!(format!("{:?}", GaussMarkovSource::GMWM), "Gmwm");
    }

    #[test]
    fn models_are_written_in_the_bank_order_without_an_absent_family() {
        let models = GaussMarkovModels::default()
            .with(GaussMarkovSource::ACF_FIT, model(3.0))
            .with(GaussMarkovSource::IRREGULAR_ML, model(2.0))
            .with(GaussMarkovSource::AR_BASED, model(1.0));
        let text = serde_json::to_string(&models).unwrap();
        let keys: Vec<usize> = ["\"ar_based\"", "\"irregular_ml\"", "\"acf_fit\""]
            .iter()
            .map(|k| text.find(k).unwrap())
            .collect();
        assert!(keys.is_sorted(), "{text}");
        assert!(!text.contains("gmwm"), "{text}");
        let back: GaussMarkovModels = serde_json::from_str(&text).unwrap();
        assert_eq!(back, models);
        // An optional family written as null, and a key of no family, read as before.
        let with_null = format!("{},\"gmwm\":null,\"later\":1}}", &text[..text.len() - 1]);
        assert_eq!(
            serde_json::from_str::<GaussMarkovModels>(&with_null).unwrap(),
            models
        );
    }

    #[test]
    fn a_family_every_bank_has_must_be_there_once() {
        let only_ml = r#"{"irregular_ml": {"status": "no_equivalent", "reason": "r"}}"#;
        let missing = serde_json::from_str::<GaussMarkovModels>(only_ml).unwrap_err();
        assert!(
            missing.to_string().starts_with("missing field `ar_based`"),
            "{missing}"
        );
        let twice = r#"{"gmwm": null, "gmwm": null}"#;
        let twice = serde_json::from_str::<GaussMarkovModels>(twice).unwrap_err();
        assert!(
            twice.to_string().starts_with("duplicate field `gmwm`"),
            "{twice}"
        );
    }

    #[test]
    fn an_absent_family_reads_as_its_reason() {
        let models = GaussMarkovModels::default();
        assert_eq!(models.estimate(GaussMarkovSource::GMWM), None);
        let GaussMarkovEstimate::NoEquivalent { reason } = models.get(GaussMarkovSource::GMWM)
        else {
            panic!("an absent family has no model");
        };
        assert!(reason.contains("--gmwm off"), "{reason}");
    }
}
