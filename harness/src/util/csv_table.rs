//! CSV text written through the `csv` crate (RFC 4180 quoting, `\n` line ends). Fields
//! arrive already formatted, so each writer keeps the digits it chose; every record must
//! have the header's field count (the crate checks it).

/// A CSV table being written into memory; [`CsvTable::finish`] gives its text.
pub struct CsvTable {
    writer: csv::Writer<Vec<u8>>,
}

impl CsvTable {
    /// A table with this header row.
    pub fn new<I, F>(header: I) -> Self
    where
        I: IntoIterator<Item = F>,
        F: AsRef<[u8]>,
    {
        let mut t = Self {
            writer: csv::WriterBuilder::new()
                .terminator(csv::Terminator::Any(b'\n'))
                .from_writer(Vec::new()),
        };
        t.row(header);
        t
    }

    /// Appends one record: as many fields as the header.
    pub fn row<I, F>(&mut self, fields: I)
    where
        I: IntoIterator<Item = F>,
        F: AsRef<[u8]>,
    {
        self.writer
            .write_record(fields)
            .expect("a record with the header's field count, written into memory");
    }

    /// The table's text.
    pub fn finish(self) -> String {
        let bytes = self
            .writer
            .into_inner()
            .expect("flushing into memory cannot fail");
        String::from_utf8(bytes).expect("fields are UTF-8 strings")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_keep_their_digits_and_odd_names_are_quoted() {
        let mut t = CsvTable::new(["frequency_Hz", "name"]);
        t.row([format!("{:.10e}", 1234.5), "tip, top".to_string()]);
        t.row(["1e-300", "say \"hi\""]);
        assert_eq!(
            t.finish(),
            "frequency_Hz,name\n1.2345000000e3,\"tip, top\"\n1e-300,\"say \"\"hi\"\"\"\n"
        );
    }

    #[test]
    fn empty_fields_stay_empty() {
        let mut t = CsvTable::new(["a", "b", "c"]);
        t.row(["1", "", "failed"]);
        assert_eq!(t.finish(), "a,b,c\n1,,failed\n");
    }
}
