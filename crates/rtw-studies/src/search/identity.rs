//! What tells two searches apart: their identities (`rtw.design`, the
//! settings and the model's options as JSON) compared key by key, so that a
//! refusal to resume names each setting that differs with both values.

/// What differs between the stored search's identity `theirs` and this
/// one's `ours` (`files::identity`): each setting and each model option, named
/// with both values (`budget 600 there, 300 here`, `contact.mu 0.5 there,
/// 0.3 here`).
pub(crate) fn differences(theirs: &serde_json::Value, ours: &serde_json::Value) -> Vec<String> {
    use std::collections::BTreeMap;
    fn flat(prefix: &str, v: &toml::Value, out: &mut BTreeMap<String, String>) {
        match v {
            toml::Value::Table(t) => {
                for (k, v) in t {
                    let key = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    flat(&key, v, out);
                }
            }
            v => {
                out.insert(prefix.to_string(), v.to_string());
            }
        }
    }
    let options = |v: &serde_json::Value| {
        let mut out = BTreeMap::new();
        if let Some(t) = v["options"]
            .as_str()
            .and_then(|t| t.parse::<toml::Table>().ok())
        {
            flat("", &toml::Value::Table(t), &mut out);
        }
        out
    };
    let settings = |v: &serde_json::Value| -> BTreeMap<String, String> {
        v["settings"]
            .as_object()
            .map(|m| m.iter().map(|(k, v)| (k.clone(), v.to_string())).collect())
            .unwrap_or_default()
    };
    let mut d = Vec::new();
    for (what, there, here) in [
        ("", settings(theirs), settings(ours)),
        ("simulation.", options(theirs), options(ours)),
    ] {
        let keys: std::collections::BTreeSet<&String> = there.keys().chain(here.keys()).collect();
        for k in keys {
            let (a, b) = (there.get(k), here.get(k));
            if a != b {
                let none = "none".to_string();
                d.push(format!(
                    "{what}{k} {} there, {} here",
                    a.unwrap_or(&none),
                    b.unwrap_or(&none)
                ));
            }
        }
    }
    if d.is_empty() {
        d.push("the same settings and options, written otherwise".into());
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_differing_setting_and_option_is_named_with_both_values() {
        let a = serde_json::json!({
            "settings": {"budget": 600, "name": "x"},
            "options": "[contact]\nmu = 0.5\n",
        });
        let b = serde_json::json!({
            "settings": {"budget": 300, "name": "x"},
            "options": "[contact]\nmu = 0.3\n",
        });
        assert_eq!(
            differences(&a, &b),
            [
                "budget 600 there, 300 here",
                "simulation.contact.mu 0.5 there, 0.3 here"
            ]
        );
    }
}
