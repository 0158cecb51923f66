//! Locating a dotted key path (`bodies[1].mass.density`) in a scene's TOML
//! text, for messages that name a line.

/// One step of a dotted key path.
enum Seg<'a> {
    Key(&'a str),
    Index(usize),
}

fn parse_path(key: &str) -> Vec<Seg<'_>> {
    let mut out = Vec::new();
    for part in key.split('.') {
        let (name, rest) = part.split_once('[').map_or((part, None), |(n, r)| (n, Some(r)));
        if !name.is_empty() {
            out.push(Seg::Key(name));
        }
        if let Some(rest) = rest {
            for idx in rest.split('[') {
                if let Ok(i) = idx.trim_end_matches(']').parse() {
                    out.push(Seg::Index(i));
                }
            }
        }
    }
    out
}

/// 1-based line of `key` in TOML `text` (of its deepest existing parent if
/// the key itself is absent); 1 if nothing matches.
pub fn line_of(text: &str, key: &str) -> usize {
    use toml::de::{DeTable, DeValue};
    let line = |offset: usize| text[..offset.min(text.len())].matches('\n').count() + 1;
    let Ok(root) = DeTable::parse(text) else {
        return 1;
    };
    let mut best = 1;
    let mut current: Option<&DeValue<'_>> = None;
    let mut table: Option<&DeTable<'_>> = Some(root.get_ref());
    for seg in parse_path(key) {
        match seg {
            Seg::Key(k) => {
                let Some(t) = table else { break };
                let Some((kk, v)) = t.iter().find(|(kk, _)| kk.get_ref().as_ref() == k) else {
                    break;
                };
                best = line(kk.span().start);
                current = Some(v.get_ref());
            }
            Seg::Index(i) => {
                let Some(DeValue::Array(a)) = current else { break };
                let Some(v) = a.get(i) else { break };
                best = line(v.span().start);
                current = Some(v.get_ref());
            }
        }
        table = match current {
            Some(DeValue::Table(t)) => Some(t),
            _ => None,
        };
    }
    best
}
