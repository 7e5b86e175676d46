//! What calls return and what reaches the master's logger.

use crate::mode::Call;

/// What an FMI call returns (`fmi2Status` without `fmi2Pending`: every call is synchronous).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Ok,
    Warning,
    Discard,
    Error,
    Fatal,
}

/// Receives the messages that pass the instance's log filter (the master's logger callback).
pub trait LogSink {
    fn log(&mut self, status: Status, category: &str, message: &str);
}

/// Which messages reach the logger: one flag per status (each status has one category),
/// decided when the selection changes, so a call checks one bool.
///
/// A message with a non-OK status (warning, discard, error, fatal) always reaches the logger,
/// whatever fmi2SetDebugLogging selected: the standard's status descriptions say the FMU calls
/// the logger for those, and a master must learn why its call failed (as the Reference FMUs'
/// logError). The selection filters the call traces (status OK, category logCalls) only: they
/// pass with debug logging on and no category given, `logCalls` or `logAll` selected.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LogFilter {
    passes: [bool; 5],
}

impl LogFilter {
    pub fn new(debug_logging: bool, categories: Option<&[&str]>) -> LogFilter {
        let passes = |status: Status| match (status, debug_logging, categories) {
            (Status::Warning | Status::Discard | Status::Error | Status::Fatal, _, _) => true,
            (Status::Ok, false, _) => false,
            (Status::Ok, true, None) => true,
            (Status::Ok, true, Some(selected)) => {
                selected.iter().any(|c| *c == status_category(status) || *c == "logAll")
            }
        };
        LogFilter { passes: STATUSES.map(passes) }
    }

    #[inline]
    pub fn passes(&self, status: Status) -> bool {
        self.passes[status as usize]
    }
}

/// What an instance logs through: the master's sink behind the filter its fmi2SetDebugLogging
/// chose (both FMUs' instances hold one).
pub struct Logger {
    filter: LogFilter,
    sink: Box<dyn LogSink>,
}

impl Logger {
    /// With debug logging as fmi2Instantiate's `loggingOn` says, no category selected.
    pub fn new(debug_logging: bool, sink: Box<dyn LogSink>) -> Logger {
        Logger { filter: LogFilter::new(debug_logging, None), sink }
    }

    /// fmi2SetDebugLogging's selection.
    pub fn select(&mut self, filter: LogFilter) {
        self.filter = filter;
    }

    /// `message` with `status`, if the filter passes it.
    pub fn emit(&mut self, status: Status, message: &str) {
        if self.filter.passes(status) {
            self.sink.log(status, status_category(status), message);
        }
    }

    /// A call trace (category logCalls); the message is only formatted when it will be sent.
    #[inline]
    pub fn trace(&mut self, message: impl FnOnce() -> String) {
        if self.filter.passes(Status::Ok) {
            let text = message();
            self.sink.log(Status::Ok, status_category(Status::Ok), &text);
        }
    }

    /// Logs "call: reason" as an error (which always passes) and returns `Error`.
    pub fn fail(&mut self, call: Call, reason: &str) -> Status {
        self.emit(Status::Error, &format!("{call}: {reason}"));
        Status::Error
    }
}

/// Every status, in the order of their discriminants.
const STATUSES: [Status; 5] = [Status::Ok, Status::Warning, Status::Discard, Status::Error, Status::Fatal];

pub fn status_category(status: Status) -> &'static str {
    match status {
        Status::Ok => "logCalls",
        Status::Warning => "logStatusWarning",
        Status::Discard => "logStatusDiscard",
        Status::Error => "logStatusError",
        Status::Fatal => "logStatusFatal",
    }
}
