//! Reading wheel and rail profile files: SIMPACK (`.prw` wheel, `.prr` rail) and MiniProf
//! (`.whl` wheel, `.ban` rail). The text is parsed here; opening the file is the caller's
//! business (the core does no I/O).
//!
//! Both readers return the profile's points in metres, y lateral, z downward (CONTACT's profile
//! coordinates), ordered by increasing y, y strictly increasing. A file whose points reverse
//! direction in y, repeat a point, hold fewer than four points, a non-number or a non-finite
//! value is refused with the line and the reason.
//!
//! SIMPACK: the `spline.begin … spline.end` block's processing options are applied in SIMPACK's
//! order, as CONTACT's `read_simpack.m` documents them — shift (`shift.y`, `shift.z`), rotation
//! about x (`rotate`, in `units.ang.f` angle units), removal of points outside
//! \[`bound.y.min`, `bound.y.max`\] and clipping of z to \[`bound.z.min`, `bound.z.max`\] (each only
//! when min < max), mirroring (`mirror.y`, `mirror.z`), inversion of the order (`inversion`), then
//! the length unit (`units.len.f` = file units per metre, 1 when absent). Everything after `!`
//! is a comment. The optional third column (a smoothing weight) is read and not used: the
//! smooth representation interpolates.
//!
//! MiniProf: a header in any of the forms MiniProf and its tools write (`Key=Value` lines, or
//! the old style's plain lines such as `#MINIWHEELPROF` and `MINIPROF 101 148 1994 3 24`, ended
//! by a blank line: see `miniprof_points`), then one point per line, columns as `ColumnDef` names
//! them (`X,Y` when absent: X lateral, Y vertical, both in mm), moved by the header's `Xoffset`
//! and `Yoffset`; everything after `"`, `!` or `%` is a comment (MiniProf comments out points
//! with a leading `"`, as CONTACT's `read_miniprof.m` reads them).
//!
//! These readers take the points as the file gives them and refuse what is not a clean profile;
//! measured, noisy, overhanging or left-side profiles are read by
//! [`super::measured_profile`], on the same lexical readers.

use std::fmt;

/// A profile file's format, chosen by its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileFormat {
    /// SIMPACK `.prw` (wheel) / `.prr` (rail).
    Simpack,
    /// MiniProf `.whl` (wheel) / `.ban` (rail).
    MiniProf,
}

impl ProfileFormat {
    /// The format of a file by its extension (case-insensitive), `None` for any other.
    pub fn from_file_name(name: &str) -> Option<Self> {
        classified(name).map(|(format, _)| format)
    }
}

/// Each profile file extension's format and the body it describes: the one table both
/// [`ProfileFormat::from_file_name`] and [`ProfileKind::from_file_name`] read.
const EXTENSIONS: [(&str, ProfileFormat, ProfileKind); 4] = [
    ("prw", ProfileFormat::Simpack, ProfileKind::Wheel),
    ("prr", ProfileFormat::Simpack, ProfileKind::Rail),
    ("whl", ProfileFormat::MiniProf, ProfileKind::Wheel),
    ("ban", ProfileFormat::MiniProf, ProfileKind::Rail),
];

/// The format and kind of a file by its extension (case-insensitive), `None` for any other.
fn classified(name: &str) -> Option<(ProfileFormat, ProfileKind)> {
    let extension = extension(name)?;
    EXTENSIONS.iter().find(|(known, ..)| *known == extension).map(|&(_, format, kind)| (format, kind))
}

/// Why a profile cannot be read: the line (1-based, when one is to blame) and the reason.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ProfileError {
    /// The file's line the error was found on, 1-based.
    pub line: Option<usize>,
    /// What is wrong.
    pub reason: String,
}

impl ProfileError {
    #[cold]
    pub(crate) fn at(line: usize, reason: impl Into<String>) -> Self {
        Self { line: Some(line), reason: reason.into() }
    }

    #[cold]
    pub(crate) fn whole(reason: impl Into<String>) -> Self {
        Self { line: None, reason: reason.into() }
    }
}

impl fmt::Display for ProfileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "line {line}: {}", self.reason),
            None => f.write_str(&self.reason),
        }
    }
}

impl std::error::Error for ProfileError {}

/// Which body a profile describes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileKind {
    Wheel,
    Rail,
}

impl ProfileKind {
    /// The kind a file's extension names (case-insensitive): `.prw`, `.whl` a wheel; `.prr`,
    /// `.ban` a rail; `None` for any other.
    pub fn from_file_name(name: &str) -> Option<Self> {
        classified(name).map(|(_, kind)| kind)
    }

    /// "wheel" or "rail".
    pub fn name(self) -> &'static str {
        match self {
            Self::Wheel => "wheel",
            Self::Rail => "rail",
        }
    }
}

/// A file name's extension, lower case.
fn extension(name: &str) -> Option<String> {
    Some(name.rsplit_once('.')?.1.to_ascii_lowercase())
}

/// How far from its origin a profile point may lie \[m\]: a wheel or rail profile spans some
/// 0.15 m (a whole rail with its foot 0.17 m), so a point 1 m away is a mistyped number or a
/// length unit off by a factor of a thousand, and reading it would size the contact search's
/// samples by it.
pub const MAX_COORDINATE: f64 = 1.0;

/// A profile's points \[m\]: y lateral, z downward, y strictly increasing.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfilePoints {
    /// y \[m\], strictly increasing.
    pub lateral: Vec<f64>,
    /// z \[m\], downward.
    pub vertical: Vec<f64>,
}

/// The fewest points the smooth representation (a cubic spline) accepts.
pub(crate) const MIN_POINTS: usize = 4;

/// Reads a profile file's text in the given format.
///
/// ```
/// use wheel_rail_contact::geometry::{parse_profile, ProfileFormat};
///
/// // A MiniProf rail (mm; `"` comments a point out), its format known by the file's extension.
/// let format = ProfileFormat::from_file_name("worn/rail.BAN").unwrap();
/// assert_eq!(format, ProfileFormat::MiniProf);
/// assert_eq!(ProfileFormat::from_file_name("rail.csv"), None);
/// let text = "Filename=rail.ban\nColumnDef=X,Y\n-2.0 1.0\n\"-1.5 9.9\n-1.0 0.25\n0.0 0.0\n1.0 0.25\n2.0 1.0\n";
/// let points = parse_profile(text, format).unwrap();
/// assert_eq!(points.lateral, [-2e-3, -1e-3, 0.0, 1e-3, 2e-3]);
/// assert_eq!(points.vertical, [1e-3, 0.25e-3, 0.0, 0.25e-3, 1e-3]);
/// // A malformed file: the error names the line and the reason.
/// let error = parse_profile("ColumnDef=X,Y\n0 0\n1 x\n", format).unwrap_err();
/// assert_eq!((error.line, error.to_string()), (Some(3), "line 3: expected a number, found `x` in `1 x`".to_string()));
/// ```
pub fn parse_profile(text: &str, format: ProfileFormat) -> Result<ProfilePoints, ProfileError> {
    match format {
        ProfileFormat::Simpack => parse_simpack(text, None),
        ProfileFormat::MiniProf => parse_miniprof(text),
    }
}

/// [`parse_profile`] of a file that must describe `kind`: a SIMPACK file's header `type`
/// (0 rail, 1 wheel), where it has one, must agree (MiniProf files say it by their extension
/// alone, [`ProfileKind::from_file_name`]).
///
/// ```
/// use wheel_rail_contact::geometry::{parse_profile_as, ProfileFormat, ProfileKind};
///
/// // The kind by the extension: a wheel's `.prw`/`.whl`, a rail's `.prr`/`.ban`.
/// assert_eq!(ProfileKind::from_file_name("worn.WHL"), Some(ProfileKind::Wheel));
/// assert_eq!(ProfileKind::from_file_name("high_rail.ban").map(ProfileKind::name), Some("rail"));
/// assert_eq!(ProfileKind::from_file_name("rail.csv"), None);
/// let wheel = "header.begin\n type = 1 ! wheel\nheader.end\nunits.len.f = 1000\n\
///              point.begin\n-20 1\n-10 0\n0 0\n10 0.5\n20 1\npoint.end\n";
/// assert!(parse_profile_as(wheel, ProfileFormat::Simpack, ProfileKind::Wheel).is_ok());
/// let error = parse_profile_as(wheel, ProfileFormat::Simpack, ProfileKind::Rail).unwrap_err();
/// assert_eq!(error.to_string(), "line 2: the header's `type = 1` says a wheel profile, not a rail profile");
/// ```
pub fn parse_profile_as(text: &str, format: ProfileFormat, kind: ProfileKind) -> Result<ProfilePoints, ProfileError> {
    match format {
        ProfileFormat::Simpack => parse_simpack(text, Some(kind)),
        ProfileFormat::MiniProf => parse_miniprof(text),
    }
}

/// A point as read, with its line for the errors found later.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RawPoint {
    pub(crate) y: f64,
    pub(crate) z: f64,
    pub(crate) line: usize,
}

/// SIMPACK's processing options (see the module doc), with SIMPACK's defaults.
struct SimpackOptions {
    shift: (f64, f64),
    rotate: f64,
    bound_y: (f64, f64),
    bound_z: (f64, f64),
    mirror_y: bool,
    mirror_z: bool,
    inversion: bool,
    length_per_metre: f64,
    angle_per_radian: f64,
}

impl Default for SimpackOptions {
    fn default() -> Self {
        Self {
            shift: (0.0, 0.0),
            rotate: 0.0,
            bound_y: (1.0, 0.0),
            bound_z: (1.0, 0.0),
            mirror_y: false,
            mirror_z: false,
            inversion: false,
            length_per_metre: 1.0,
            angle_per_radian: 1.0,
        }
    }
}

fn parse_simpack(text: &str, kind: Option<ProfileKind>) -> Result<ProfilePoints, ProfileError> {
    let (points, units) = simpack_points(text, kind)?;
    finish(points, &units)
}

/// A SIMPACK file's points in metres in the file's order, its options applied (module doc), and
/// how its lengths were read (for the messages).
pub(crate) fn simpack_points(text: &str, kind: Option<ProfileKind>) -> Result<(Vec<RawPoint>, String), ProfileError> {
    let mut options = SimpackOptions::default();
    let mut points = Vec::new();
    let mut in_points = false;
    let mut in_header = false;
    let mut seen_points = false;
    for (index, raw_line) in text.lines().enumerate() {
        let line = index + 1;
        let content = raw_line.split('!').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        match content {
            "point.begin" => {
                in_points = true;
                seen_points = true;
                continue;
            }
            "point.end" => {
                in_points = false;
                continue;
            }
            "header.begin" => {
                in_header = true;
                continue;
            }
            "header.end" => {
                in_header = false;
                continue;
            }
            _ => {}
        }
        if in_points {
            points.push(parse_point(content, line, (0, 1))?);
        } else if let Some((key, value)) = content.split_once('=') {
            let (key, value) = (key.trim(), value.trim());
            // The header's `type` says wheel or rail (the spline block's `type` is the original
            // data file's, another thing).
            if in_header && key == "type" {
                check_simpack_type(value, kind, line)?;
            } else {
                apply_simpack_option(&mut options, key, value, line)?;
            }
        }
    }
    if !seen_points {
        return Err(ProfileError::whole("no `point.begin` block: not a SIMPACK profile"));
    }
    if in_points {
        return Err(ProfileError::at(text.lines().count(), "`point.begin` without `point.end`"));
    }
    let points = process_simpack(points, &options);
    let units = format!(" (units.len.f = {} file units per metre: millimetres need 1000)", options.length_per_metre);
    Ok((points, units))
}

/// A SIMPACK header's `type` against the kind the file is read as.
fn check_simpack_type(value: &str, kind: Option<ProfileKind>, line: usize) -> Result<(), ProfileError> {
    let (number, declared) = match value.parse::<i64>() {
        Ok(0) => (0, ProfileKind::Rail),
        Ok(1) => (1, ProfileKind::Wheel),
        _ => {
            return Err(ProfileError::at(
                line,
                format!("the header's `type` must be 0 (rail) or 1 (wheel), found `{value}`"),
            ))
        }
    };
    match kind {
        Some(kind) if kind != declared => Err(ProfileError::at(
            line,
            format!("the header's `type = {number}` says a {} profile, not a {} profile", declared.name(), kind.name()),
        )),
        _ => Ok(()),
    }
}

fn apply_simpack_option(options: &mut SimpackOptions, key: &str, value: &str, line: usize) -> Result<(), ProfileError> {
    let number = || -> Result<f64, ProfileError> {
        value
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| ProfileError::at(line, format!("`{key}` must be a finite number, found `{value}`")))
    };
    let flag = || -> Result<bool, ProfileError> {
        match value {
            "0" => Ok(false),
            "1" => Ok(true),
            _ => Err(ProfileError::at(line, format!("`{key}` must be 0 or 1, found `{value}`"))),
        }
    };
    match key {
        "shift.y" => options.shift.0 = number()?,
        "shift.z" => options.shift.1 = number()?,
        "rotate" => options.rotate = number()?,
        "bound.y.min" => options.bound_y.0 = number()?,
        "bound.y.max" => options.bound_y.1 = number()?,
        "bound.z.min" => options.bound_z.0 = number()?,
        "bound.z.max" => options.bound_z.1 = number()?,
        "mirror.y" => options.mirror_y = flag()?,
        "mirror.z" => options.mirror_z = flag()?,
        "inversion" => options.inversion = flag()?,
        "units.len.f" | "units.ang.f" => {
            let factor = number()?;
            if factor <= 0.0 {
                return Err(ProfileError::at(line, format!("`{key}` must be > 0, found `{value}`")));
            }
            if key == "units.len.f" {
                options.length_per_metre = factor;
            } else {
                options.angle_per_radian = factor;
            }
        }
        // Other header data (version, type, file names, comments) does not change the points.
        _ => {}
    }
    Ok(())
}

/// SIMPACK's modifications in its order (module doc), the result in metres.
fn process_simpack(mut points: Vec<RawPoint>, options: &SimpackOptions) -> Vec<RawPoint> {
    let (sin, cos) = (options.rotate / options.angle_per_radian).sin_cos();
    for p in &mut points {
        let (y, z) = (p.y + options.shift.0, p.z + options.shift.1);
        (p.y, p.z) = (cos * y - sin * z, sin * y + cos * z);
    }
    let (y_min, y_max) = options.bound_y;
    if y_min < y_max {
        points.retain(|p| (y_min..=y_max).contains(&p.y));
    }
    let (z_min, z_max) = options.bound_z;
    for p in &mut points {
        if z_min < z_max {
            p.z = p.z.clamp(z_min, z_max);
        }
        if options.mirror_y {
            p.y = -p.y;
        }
        if options.mirror_z {
            p.z = -p.z;
        }
        p.y /= options.length_per_metre;
        p.z /= options.length_per_metre;
    }
    if options.inversion {
        points.reverse();
    }
    points
}

fn parse_miniprof(text: &str) -> Result<ProfilePoints, ProfileError> {
    finish(miniprof_points(text)?, MINIPROF_UNITS)
}

/// How MiniProf's lengths are read, for the messages.
pub(crate) const MINIPROF_UNITS: &str = " (MiniProf files are in millimetres)";

/// A MiniProf file's points in metres, in the file's order, moved by the header's `Xoffset`
/// and `Yoffset` (added, as CONTACT's reader does). The header forms MiniProf and the tools around it
/// write, as CONTACT's `read_miniprof_profile` (m_profile.f90) tells them apart: `Key=Value`
/// lines; the old style's plain lines (`#MINIWHEELPROF`, `MINIPROF 101 148 1994 3 24`, the file
/// name, `Stock.......:`, `32.58 37.11 14.71  (Sd/Sh/qR)`), after which numbers belong to the
/// header until its blank line; a blank line ends a header. Without an old-style line, the first
/// line of numbers starts the points. A `Key=` line among the points, or a point that is not
/// numbers, is refused with its line.
pub(crate) fn miniprof_points(text: &str) -> Result<Vec<RawPoint>, ProfileError> {
    let mut columns = (0, 1);
    let mut points = Vec::new();
    let mut offset = (0.0, 0.0);
    let (mut in_header, mut old_style, mut header_seen) = (true, false, false);
    for (index, raw_line) in text.lines().enumerate() {
        let line = index + 1;
        let trimmed = raw_line.trim();
        if trimmed.is_empty() {
            in_header &= !header_seen;
            continue;
        }
        // A whole line commented out (a point MiniProf dropped, a quoted header line).
        if trimmed.starts_with(['"', '!', '%']) {
            continue;
        }
        // A comment may hold a `=` (`0.5 1.2 ! x=3`); a header value may start with `%`.
        let content = trimmed.split(['"', '!', '%']).next().unwrap_or("").trim();
        if let Some((key, value)) = trimmed.split_once('=').filter(|_| content.contains('=')) {
            if !in_header {
                return Err(ProfileError::at(line, format!("a header line `{trimmed}` among the points")));
            }
            header_seen = true;
            // MiniProf marks a text value with `%` (`Side=%L`).
            let value = value.trim().trim_start_matches('%');
            match key.trim() {
                "ColumnDef" => columns = miniprof_columns(value, line)?,
                "Xoffset" | "XOffset" => offset.0 = miniprof_header_number(key, value, line)? * 1e-3,
                "Yoffset" | "YOffset" => offset.1 = miniprof_header_number(key, value, line)? * 1e-3,
                _ => {}
            }
            continue;
        }
        let numeric = content
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|f| !f.is_empty())
            .all(|f| f.parse::<f64>().is_ok());
        if in_header {
            if trimmed.starts_with('#') || !numeric {
                (old_style, header_seen) = (true, true);
                continue;
            }
            if old_style {
                continue;
            }
            in_header = false;
        }
        let point = parse_point(content, line, columns)?;
        // MiniProf writes millimetres.
        points.push(RawPoint { y: point.y * 1e-3 + offset.0, z: point.z * 1e-3 + offset.1, line });
    }
    Ok(points)
}

/// A MiniProf header's number (empty: 0, as MiniProf leaves unused offsets blank).
fn miniprof_header_number(key: &str, value: &str, line: usize) -> Result<f64, ProfileError> {
    if value.is_empty() {
        return Ok(0.0);
    }
    value
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| ProfileError::at(line, format!("`{}` must be a finite number, found `{value}`", key.trim())))
}

/// The positions of the X (lateral) and Y (vertical) columns in a MiniProf `ColumnDef`.
fn miniprof_columns(definition: &str, line: usize) -> Result<(usize, usize), ProfileError> {
    let names: Vec<&str> = definition.split(',').map(str::trim).collect();
    let find = |name: &str| names.iter().position(|n| n.eq_ignore_ascii_case(name));
    match (find("X"), find("Y")) {
        (Some(x), Some(y)) => Ok((x, y)),
        _ => Err(ProfileError::at(line, format!("`ColumnDef={definition}` names no X and Y columns"))),
    }
}

/// One data line: numbers separated by white space or commas; `columns` are (y, z)'s positions.
fn parse_point(content: &str, line: usize, columns: (usize, usize)) -> Result<RawPoint, ProfileError> {
    let fields: Vec<&str> = content.split(|c: char| c.is_whitespace() || c == ',').filter(|f| !f.is_empty()).collect();
    let value = |column: usize| -> Result<f64, ProfileError> {
        let field = fields.get(column).ok_or_else(|| {
            ProfileError::at(line, format!("expected a point (y z), found `{content}`: too few columns"))
        })?;
        let number = field
            .parse::<f64>()
            .map_err(|_| ProfileError::at(line, format!("expected a number, found `{field}` in `{content}`")))?;
        if number.is_finite() {
            Ok(number)
        } else {
            Err(ProfileError::at(line, format!("the value `{field}` is not finite")))
        }
    };
    Ok(RawPoint { y: value(columns.0)?, z: value(columns.1)?, line })
}

/// Checks that every point lies within [`MAX_COORDINATE`] of the origin (`units` says how the
/// file's lengths were read, for the message), orders the points by increasing y and checks
/// that y is strictly monotonic.
pub(crate) fn finish(mut points: Vec<RawPoint>, units: &str) -> Result<ProfilePoints, ProfileError> {
    if let Some(far) = points.iter().find(|p| p.y.abs().max(p.z.abs()) > MAX_COORDINATE) {
        return Err(ProfileError::at(
            far.line,
            format!(
                "the point (y, z) = ({:e}, {:e}) m lies more than {MAX_COORDINATE} m from the profile's origin: not a \
                 wheel or rail profile in these units{units}",
                far.y, far.z
            ),
        ));
    }
    if points.len() < MIN_POINTS {
        return Err(ProfileError::whole(format!(
            "{} profile points; a profile needs at least {MIN_POINTS}",
            points.len()
        )));
    }
    if points[points.len() - 1].y < points[0].y {
        points.reverse();
    }
    for pair in points.windows(2) {
        if pair[1].y <= pair[0].y {
            return Err(ProfileError::at(
                pair[1].line,
                format!(
                    "the profile is not monotonic in y: y = {} mm follows y = {} mm (line {})",
                    pair[1].y * 1e3,
                    pair[0].y * 1e3,
                    pair[0].line
                ),
            ));
        }
    }
    Ok(ProfilePoints { lateral: points.iter().map(|p| p.y).collect(), vertical: points.iter().map(|p| p.z).collect() })
}
