//! Measured rebounds read from CSV: one header row, then one row per bounce. A column named by a
//! parameter flag (`angle`, `cart-mass`; the scenario key `cart_mass` too) gives that row's condition, a
//! bare number in the flag's base unit or with a unit suffix (`56mph`, `-3820rpm`). A column named by a
//! [`Quantity`] (`omega2`, `theta2_deg`, ...) is a measurement, a bare number in the quantity's unit, and
//! `sigma_<quantity>` its standard uncertainty (above 0). A text column named in [`Layout::group`] splits
//! the rows into groups (string beds, say), and columns named in [`Layout::ignore`] are labels left
//! unread. A UTF-8 byte-order mark (as a spreadsheet saves it) is skipped, and so are blank lines and
//! lines starting with `#`. Every other cell must hold a value; the first bad one is an error naming
//! file, line and column.

use std::fmt;

use crate::model::params::{ParamId, Params, spec, spec_named};
use crate::model::{Bounce, ParamError};

/// A rebound quantity that can be measured: its column name, unit and value in a solved bounce.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    Omega2,
    Omega2Rpm,
    Vx2,
    Vy2,
    Theta2Deg,
    Ex,
    Speed2,
}

impl Quantity {
    pub const ALL: [Quantity; 7] = [
        Quantity::Omega2,
        Quantity::Omega2Rpm,
        Quantity::Vx2,
        Quantity::Vy2,
        Quantity::Theta2Deg,
        Quantity::Ex,
        Quantity::Speed2,
    ];

    /// The column name, also the key in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Omega2 => "omega2",
            Quantity::Omega2Rpm => "omega2_rpm",
            Quantity::Vx2 => "vx2",
            Quantity::Vy2 => "vy2",
            Quantity::Theta2Deg => "theta2_deg",
            Quantity::Ex => "ex",
            Quantity::Speed2 => "speed2",
        }
    }

    /// The unit of the column's numbers (`""` for a pure number).
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::Omega2 => "rad/s",
            Quantity::Omega2Rpm => "rpm",
            Quantity::Vx2 | Quantity::Vy2 | Quantity::Speed2 => "m/s",
            Quantity::Theta2Deg => "deg",
            Quantity::Ex => "",
        }
    }

    pub fn named(name: &str) -> Option<Quantity> {
        Quantity::ALL.into_iter().find(|q| q.name() == name)
    }

    /// The quantity in a solved bounce; `None` for e_x when the ball arrives without slip.
    pub fn of(self, bounce: &Bounce) -> Option<f64> {
        let o = &bounce.outcome;
        match self {
            Quantity::Omega2 => Some(o.omega2),
            Quantity::Omega2Rpm => Some(o.omega2 * 30.0 / std::f64::consts::PI),
            Quantity::Vx2 => Some(o.vx2),
            Quantity::Vy2 => Some(o.vy2),
            Quantity::Theta2Deg => Some(o.theta2_deg),
            Quantity::Ex => o.ex,
            Quantity::Speed2 => Some(o.speed2()),
        }
    }
}

/// One measured value with its standard uncertainty, if the data give one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measurement {
    pub quantity: Quantity,
    pub value: f64,
    pub sigma: Option<f64>,
}

/// One bounce of the data: where it is in the file, its conditions and what was measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Line in the file, from 1.
    pub line: usize,
    /// The row's group, an index into [`Dataset::groups`]; `None` without a group column.
    pub group: Option<usize>,
    pub conditions: Vec<(ParamId, f64)>,
    pub measured: Vec<Measurement>,
}

impl Row {
    /// `base` with this row's conditions.
    pub fn params(&self, base: &Params) -> Params {
        let mut p = *base;
        for &(id, value) in &self.conditions {
            p.set(id, value);
        }
        p
    }
}

/// A data set: its rows and where it came from (for messages).
#[derive(Clone, Debug, PartialEq)]
pub struct Dataset {
    pub origin: String,
    pub rows: Vec<Row>,
    /// The parameters the columns set.
    pub conditions: Vec<ParamId>,
    /// True when every measured quantity has a `sigma_` column: the uncertainties are absolute.
    pub absolute_sigma: bool,
    /// The labels of the groups, in the order they first appear (empty without a group column).
    pub groups: Vec<String>,
}

/// How to read the columns that are not conditions or measurements.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Layout {
    /// A text column whose labels split the rows into groups.
    pub group: Option<String>,
    /// Columns to leave unread (labels: the string's name, the company).
    pub ignore: Vec<String>,
}

/// The conditions of a bounce that a row may set: how the ball arrives.
pub const INCOMING: [ParamId; 3] = [ParamId::Angle, ParamId::Speed, ParamId::Spin];

impl Dataset {
    /// How many values were measured in all.
    pub fn measurements(&self) -> usize {
        self.rows.iter().map(|r| r.measured.len()).sum()
    }

    /// The incoming conditions no column sets, with their value in `base` (SI): every row takes it.
    pub fn assumed(&self, base: &Params) -> Vec<(ParamId, f64)> {
        INCOMING
            .into_iter()
            .filter(|id| !self.conditions.contains(id))
            .map(|id| (id, base.get(id)))
            .collect()
    }
}

/// A cell or header that cannot be read: `file:line:column: message`.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{origin}:{line}:{column}: {message}")]
pub struct DataError {
    pub origin: String,
    pub line: usize,
    pub column: usize,
    pub message: String,
}

/// What a column holds.
#[derive(Clone, Copy, Debug)]
enum Column {
    Condition(ParamId),
    Value(Quantity),
    Sigma(Quantity),
    /// The group column's labels.
    Group,
    /// A column left unread.
    Ignored,
}

impl Column {
    fn named(name: &str) -> Option<Column> {
        if let Some(q) = name.strip_prefix("sigma_").and_then(Quantity::named) {
            return Some(Column::Sigma(q));
        }
        Quantity::named(name)
            .map(Column::Value)
            .or_else(|| spec_named(name).map(|s| Column::Condition(s.id)))
    }
}

fn expected_columns() -> String {
    let quantities: Vec<_> = Quantity::ALL.iter().map(|q| q.name()).collect();
    format!(
        "expected a parameter flag (angle, speed, spin, cart-mass, ...), a measured quantity ({}) or sigma_ \
         and a quantity",
        quantities.join(", ")
    )
}

/// Reads CSV `text`; `origin` names it in messages.
pub fn parse(text: &str, origin: &str) -> Result<Dataset, DataError> {
    parse_with(text, origin, &Layout::default())
}

/// [`parse`], with a group column and ignored columns as `layout` names them.
pub fn parse_with(text: &str, origin: &str, layout: &Layout) -> Result<Dataset, DataError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let err = |line: usize, column: usize, message: String| DataError {
        origin: origin.to_string(),
        line,
        column,
        message,
    };
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim_end_matches('\r')))
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let Some((header_line, header)) = lines.next() else {
        return Err(err(1, 1, "no header row: the data are empty".into()));
    };
    let mut columns = Vec::new();
    for (i, name) in header.split(',').map(str::trim).enumerate() {
        let column = if layout.group.as_deref() == Some(name) {
            Some(Column::Group)
        } else if layout.ignore.iter().any(|c| c == name) {
            Some(Column::Ignored)
        } else {
            Column::named(name)
        };
        let column = column.ok_or_else(|| {
            err(
                header_line,
                i + 1,
                format!(
                    "unknown column '{name}': {}{}",
                    expected_columns(),
                    if layout.ignore.is_empty() {
                        "; --ignore leaves a label column unread"
                    } else {
                        ""
                    }
                ),
            )
        })?;
        if columns.iter().any(|c: &Column| same(*c, column)) {
            return Err(err(
                header_line,
                i + 1,
                format!("column '{name}' appears twice"),
            ));
        }
        columns.push(column);
    }
    let measured: Vec<Quantity> = columns
        .iter()
        .filter_map(|c| match c {
            Column::Value(q) => Some(*q),
            _ => None,
        })
        .collect();
    if measured.is_empty() {
        return Err(err(
            header_line,
            1,
            "no measured column: name one of omega2, omega2_rpm, vx2, vy2, theta2_deg, ex, speed2"
                .into(),
        ));
    }
    for (i, c) in columns.iter().enumerate() {
        if let Column::Sigma(q) = c
            && !measured.contains(q)
        {
            return Err(err(
                header_line,
                i + 1,
                format!("sigma_{0} without the column {0}", q.name()),
            ));
        }
    }
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    for (wanted, flag) in layout
        .group
        .iter()
        .map(|g| (g, "--group"))
        .chain(layout.ignore.iter().map(|c| (c, "--ignore")))
    {
        if !names.contains(&wanted.as_str()) {
            return Err(err(
                header_line,
                1,
                format!(
                    "{flag}: no column '{wanted}' (the columns are {})",
                    names.join(", ")
                ),
            ));
        }
    }
    let mut groups: Vec<String> = Vec::new();
    let mut rows = Vec::new();
    for (line, text) in lines {
        let cells: Vec<&str> = text.split(',').map(str::trim).collect();
        if cells.len() > columns.len() {
            return Err(err(
                line,
                columns.len() + 1,
                format!(
                    "{} values where the header names {} columns",
                    cells.len(),
                    columns.len()
                ),
            ));
        }
        let mut row = Row {
            line,
            group: None,
            conditions: Vec::new(),
            measured: Vec::new(),
        };
        let mut sigmas = Vec::new();
        for (i, column) in columns.iter().enumerate() {
            let at = |message: String| err(line, i + 1, message);
            let cell = match cells.get(i) {
                Some(c) if !c.is_empty() => *c,
                _ if matches!(column, Column::Ignored) => "",
                _ => return Err(at(format!("missing value for {}", header_name(*column)))),
            };
            match *column {
                Column::Ignored => {}
                Column::Group => {
                    let index = groups.iter().position(|g| g == cell).unwrap_or_else(|| {
                        groups.push(cell.to_string());
                        groups.len() - 1
                    });
                    row.group = Some(index);
                }
                Column::Condition(id) => {
                    let value = spec(id).parse(cell).map_err(|e| at(condition_error(e)))?;
                    row.conditions.push((id, value));
                }
                Column::Value(quantity) => {
                    let value = number(cell).map_err(at)?;
                    row.measured.push(Measurement {
                        quantity,
                        value,
                        sigma: None,
                    });
                }
                Column::Sigma(quantity) => {
                    let sigma = number(cell).map_err(&at)?;
                    if sigma <= 0.0 {
                        return Err(at(format!(
                            "sigma_{} must be above 0; got {cell}",
                            quantity.name()
                        )));
                    }
                    sigmas.push((quantity, sigma));
                }
            }
        }
        for (quantity, sigma) in sigmas {
            if let Some(m) = row.measured.iter_mut().find(|m| m.quantity == quantity) {
                m.sigma = Some(sigma);
            }
        }
        rows.push(row);
    }
    if rows.is_empty() {
        return Err(err(
            header_line + 1,
            1,
            "no data rows after the header".into(),
        ));
    }
    let absolute_sigma = measured.iter().all(|q| {
        columns
            .iter()
            .any(|c| matches!(c, Column::Sigma(s) if s == q))
    });
    let conditions = columns
        .iter()
        .filter_map(|c| match c {
            Column::Condition(id) => Some(*id),
            _ => None,
        })
        .collect();
    Ok(Dataset {
        origin: origin.to_string(),
        rows,
        conditions,
        absolute_sigma,
        groups,
    })
}

fn same(a: Column, b: Column) -> bool {
    match (a, b) {
        (Column::Condition(x), Column::Condition(y)) => x == y,
        (Column::Value(x), Column::Value(y)) | (Column::Sigma(x), Column::Sigma(y)) => x == y,
        (Column::Group, Column::Group) => true,
        _ => false,
    }
}

fn header_name(column: Column) -> String {
    match column {
        Column::Condition(id) => spec(id).flag.to_string(),
        Column::Value(q) => q.name().to_string(),
        Column::Sigma(q) => format!("sigma_{}", q.name()),
        Column::Group => "the group".to_string(),
        Column::Ignored => "an ignored column".to_string(),
    }
}

/// A parameter error without the leading `--flag`, which the column already names.
fn condition_error(e: ParamError) -> String {
    match e {
        ParamError::OutOfRange {
            flag, range, given, ..
        } => format!("{flag} must be in {range}; got {given}"),
        ParamError::Unparsable {
            flag,
            given,
            source,
        } => format!("{flag}: {source}; got {given}"),
    }
}

fn number(cell: &str) -> Result<f64, String> {
    match cell.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("'{cell}' is not a number")),
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_conditions_with_units_measurements_and_sigmas() {
        let text = "# synthetic\nangle,spin,omega2_rpm,sigma_omega2_rpm\n40,-3820rpm,2500,50\n\n50deg,0,1800,60\n";
        let data = parse(text, "d.csv").unwrap();
        assert_eq!(data.rows.len(), 2);
        assert_eq!(data.rows[0].line, 3);
        assert_eq!(data.rows[1].line, 5);
        assert!((data.rows[0].conditions[1].1 + 3820.0 * std::f64::consts::PI / 30.0).abs() < 1e-9);
        assert_eq!(data.rows[1].measured[0].sigma, Some(60.0));
        assert!(data.absolute_sigma);
        assert_eq!(data.conditions, vec![ParamId::Angle, ParamId::Spin]);
    }

    #[test]
    fn bad_cells_name_file_line_and_column() {
        let e = parse("angle,omega3\n40,1\n", "d.csv").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("d.csv:1:2: unknown column 'omega3'"),
            "{e}"
        );
        let e = parse("angle,omega2\n40,1\n50\n", "d.csv").unwrap_err();
        assert_eq!(e.to_string(), "d.csv:3:2: missing value for omega2");
        let e = parse("angle,omega2\n40,x1\n", "d.csv").unwrap_err();
        assert_eq!(e.to_string(), "d.csv:2:2: 'x1' is not a number");
        let e = parse("angle,omega2\n95,1\n", "d.csv").unwrap_err();
        assert_eq!(
            e.to_string(),
            "d.csv:2:1: angle must be in (0, 90] deg; got 95"
        );
        let e = parse("angle,omega2,sigma_omega2\n40,1,0\n", "d.csv").unwrap_err();
        assert_eq!(
            e.to_string(),
            "d.csv:2:3: sigma_omega2 must be above 0; got 0"
        );
        let e = parse("angle,sigma_ex,omega2\n40,1,2\n", "d.csv").unwrap_err();
        assert_eq!(e.to_string(), "d.csv:1:2: sigma_ex without the column ex");
        let e = parse("angle\n40\n", "d.csv").unwrap_err();
        assert!(
            e.to_string().starts_with("d.csv:1:1: no measured column"),
            "{e}"
        );
    }

    #[test]
    fn a_byte_order_mark_is_skipped() {
        let data = parse("\u{feff}angle,omega2\n40,1\n", "d.csv").unwrap();
        assert_eq!(data.conditions, vec![ParamId::Angle]);
        // The incoming conditions no column sets are named, at the base's values.
        let base = Params::default();
        assert_eq!(
            data.assumed(&base),
            vec![(ParamId::Speed, base.speed), (ParamId::Spin, base.spin)]
        );
    }

    #[test]
    fn a_group_column_splits_the_rows_and_ignored_columns_are_left_unread() {
        let layout = Layout {
            group: Some("material".into()),
            ignore: vec!["string".into(), "company".into()],
        };
        let text =
            "company,string,material,angle,omega2\nA,x,poly,40,1\nB,y,nylon,40,2\n,z,poly,50,3\n";
        let data = parse_with(text, "d.csv", &layout).unwrap();
        assert_eq!(data.groups, vec!["poly", "nylon"]);
        let groups: Vec<_> = data.rows.iter().map(|r| r.group).collect();
        assert_eq!(groups, vec![Some(0), Some(1), Some(0)]);
        let e = parse("company,angle,omega2\nA,40,1\n", "d.csv").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("d.csv:1:1: unknown column 'company'"),
            "{e}"
        );
        let e = parse_with("angle,omega2\n40,1\n", "d.csv", &layout).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("d.csv:1:1: --group: no column 'material'"),
            "{e}"
        );
        let only_group = Layout {
            group: layout.group.clone(),
            ignore: Vec::new(),
        };
        let e = parse_with(
            "material,angle,omega2\npoly,40,1\n,50,2\n",
            "d.csv",
            &only_group,
        );
        assert_eq!(
            e.unwrap_err().to_string(),
            "d.csv:3:1: missing value for the group"
        );
    }
}
