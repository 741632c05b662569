//! The list of the paper's numbers, `assets/claims.md` (a copy of the project's claims list, embedded so
//! the program stands alone): one claim per table row, `| id | where | statement |`.

/// The claims file as shipped.
pub const CLAIMS_MD: &str = include_str!("../../assets/claims.md");

/// One row of the claims table.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Claim {
    pub id: String,
    /// Where the paper states it, e.g. `Fig. 3(b)`.
    pub place: String,
    pub statement: String,
}

/// Every claim of `text`, in order: the rows of its table after the header and the separator.
pub fn parse(text: &str) -> Vec<Claim> {
    text.lines()
        .map(str::trim)
        .filter(|line| line.starts_with('|') && line.ends_with('|'))
        .filter_map(|line| {
            let cells: Vec<&str> = line[1..line.len() - 1].split('|').map(str::trim).collect();
            match cells.as_slice() {
                [id, place, statement] => Some((*id, *place, *statement)),
                _ => None,
            }
        })
        .filter(|(id, _, _)| *id != "id" && !id.starts_with("---"))
        .map(|(id, place, statement)| Claim {
            id: id.to_string(),
            place: place.to_string(),
            statement: statement.to_string(),
        })
        .collect()
}

/// The claims of the shipped file.
pub fn all() -> Vec<Claim> {
    parse(CLAIMS_MD)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_every_row_of_the_shipped_list() {
        let claims = all();
        assert_eq!(claims.len(), 18);
        assert_eq!(claims[0].id, "eq8-coefficient");
        assert_eq!(claims[0].place, "Sec. III, Eq. (8)");
        assert!(claims[0].statement.contains("440.8"));
        assert_eq!(claims.last().unwrap().id, "heavy-normal");
    }
}
