//! Any bytes given to the GPU-dump reader: packets or an error, never a panic; every packet
//! read is written again by the writer in both dialects and read back as the same packet;
//! the dump converts to command-stream text and back without error.
#![no_main]

use gpu::command_stream::{from_dump, parse_entries, to_dump};
use gpu::dump::{Dialect, Reader, Writer};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(reader) = Reader::new(data) else {
        return;
    };
    let dialect = reader.dialect();
    let mut copy = Writer::new(Vec::new(), dialect).unwrap();
    let mut count = 0usize;
    for item in reader.clone() {
        let Ok((_, packet)) = item else { break };
        let _ = format!("{packet:?}");
        // Unknown packets with a known type byte cannot occur: the reader types them.
        copy.packet(&packet).unwrap();
        count += 1;
    }
    let copy = copy.into_inner();
    let again: Vec<_> = Reader::new(&copy).unwrap().collect();
    assert_eq!(again.len(), count);
    let originals = reader.take(count).map(|p| p.unwrap().1);
    for (a, b) in originals.zip(again) {
        assert_eq!(a, b.unwrap().1);
    }
    // Text and back.
    let mut text = String::new();
    if from_dump(Reader::new(&copy).unwrap(), &mut text).is_ok() {
        let entries = parse_entries(&text).unwrap();
        let mut w = Writer::new(Vec::new(), Dialect::Spec).unwrap();
        to_dump(&entries, &mut w).unwrap();
    }
});
