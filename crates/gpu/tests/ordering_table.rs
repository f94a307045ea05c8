//! Ordering-table clear, insertion and DMA2 walk (docs/hardware/gpu.md §2), checked against hand-built
//! linked lists.

use gpu::{END_MARKER, OrderingTable, OtError, walk_ram};

fn collect(ot: &OrderingTable) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    ot.walk(|w| out.push(w.to_vec())).unwrap();
    out
}

#[test]
fn clear_builds_reverse_linked_empty_entries() {
    let ot = OrderingTable::new(4, 16).unwrap();
    // Entry 0 holds the terminator, entry i links to entry i-1 (byte address 4*(i-1)).
    assert_eq!(&ot.ram()[..4], &[0x00FF_FFFF, 0, 4, 8]);
    assert_eq!(END_MARKER, 0x00FF_FFFF);
    let stats = ot
        .walk(|_| panic!("an empty table delivers no words"))
        .unwrap();
    assert_eq!(stats.nodes, 4);
    assert_eq!(stats.packets, 0);
    assert_eq!(stats.words, 0);
}

#[test]
fn walk_goes_from_far_end_to_near_end() {
    let mut ot = OrderingTable::new(8, 64).unwrap();
    ot.insert(1, &[0x1111_1111]).unwrap();
    ot.insert(7, &[0x7777_7777, 0x7777_0001]).unwrap();
    ot.insert(0, &[0x0000_0000]).unwrap();
    ot.insert(4, &[0x4444_4444]).unwrap();
    assert_eq!(
        collect(&ot),
        vec![
            vec![0x7777_7777, 0x7777_0001],
            vec![0x4444_4444],
            vec![0x1111_1111],
            vec![0x0000_0000],
        ]
    );
    // Headers: 8 entries then node at word 8 (index 1 packet): 1 word, links to entry 0.
    assert_eq!(ot.ram()[8], 1 << 24);
    assert_eq!(ot.ram()[1], 8 * 4);
}

#[test]
fn same_index_packets_come_out_most_recent_first() {
    let mut ot = OrderingTable::new(2, 32).unwrap();
    ot.insert(1, &[0xA]).unwrap();
    ot.insert(1, &[0xB]).unwrap();
    ot.insert(1, &[0xC]).unwrap();
    assert_eq!(collect(&ot), vec![vec![0xC], vec![0xB], vec![0xA]]);
}

#[test]
fn clear_empties_the_primitive_buffer() {
    let mut ot = OrderingTable::new(2, 8).unwrap();
    ot.insert(1, &[1, 2, 3]).unwrap();
    assert_eq!(ot.used_words(), 4);
    ot.clear();
    assert_eq!(ot.used_words(), 0);
    assert!(collect(&ot).is_empty());
}

#[test]
fn insertion_errors() {
    let mut ot = OrderingTable::new(2, 5).unwrap();
    assert_eq!(
        ot.insert(2, &[0]),
        Err(OtError::IndexOutOfRange { index: 2, depth: 2 })
    );
    assert_eq!(ot.insert(0, &[0; 256]), Err(OtError::PacketTooLong(256)));
    ot.insert(0, &[1, 2, 3, 4]).unwrap(); // header + 4 words fill the 5-word buffer
    assert_eq!(ot.insert(0, &[5]), Err(OtError::PrimitiveBufferFull));
}

#[test]
fn walk_ram_follows_hand_built_list_to_terminator() {
    // Start at byte 0x10: 2 words, next 0x00; at 0x00: 1 word, next 0x08;
    // at 0x08: empty node with the terminator.
    let ram = [
        0x0100_0008,
        0xDEAD_0001,
        0x00FF_FFFF,
        0,
        0x0200_0000,
        0xBEEF_0001,
        0xBEEF_0002,
    ];
    let mut seen = Vec::new();
    let stats = walk_ram(&ram, 0x10, |w| seen.push(w.to_vec())).unwrap();
    assert_eq!(
        seen,
        vec![vec![0xBEEF_0001, 0xBEEF_0002], vec![0xDEAD_0001]]
    );
    assert_eq!(stats.nodes, 3);
    assert_eq!(stats.packets, 2);
    assert_eq!(stats.words, 3);
}

#[test]
fn any_link_with_bit_23_set_ends_the_walk() {
    let ram = [0x0180_0000, 0x1234_5678];
    let mut seen = Vec::new();
    walk_ram(&ram, 0, |w| seen.push(w.to_vec())).unwrap();
    assert_eq!(seen, vec![vec![0x1234_5678]]);
}

#[test]
fn bad_links_end_the_walk_with_an_error() {
    // Link to byte 0x40, past the 3-word buffer.
    let ram = [0x0000_0040, 0, 0];
    assert_eq!(walk_ram(&ram, 0, |_| {}), Err(OtError::BadLink(0x40)));
    // Start outside the buffer.
    assert_eq!(walk_ram(&ram, 0x0C, |_| {}), Err(OtError::BadLink(0x0C)));
    // Word count running past the end of the buffer.
    let ram = [0x0500_0000, 1, 2];
    assert_eq!(walk_ram(&ram, 0, |_| {}), Err(OtError::BadLink(0)));
}

#[test]
fn cycles_are_detected() {
    // 0x00 -> 0x04 -> 0x00 -> ...
    let ram = [0x0000_0004, 0x0000_0000];
    assert_eq!(walk_ram(&ram, 0, |_| {}), Err(OtError::Cycle));
    // A node linking to itself.
    let ram = [0x0100_0000, 0xE100_0000];
    let mut delivered = 0usize;
    assert_eq!(walk_ram(&ram, 0, |_| delivered += 1), Err(OtError::Cycle));
    assert!(delivered <= ram.len() + 1);
}

/// Links are 24-bit byte addresses with bit 23 as the end marker: entry `i` sits at byte
/// address 4 * i, so a table and its buffer span at most 2^21 words (byte addresses below
/// 80_0000h). 2^21 - 1 entries are accepted, 2^21 refused with an error naming the limit.
#[test]
fn depth_limit() {
    let limit = 1usize << 21;
    assert!(OrderingTable::new(limit - 1, 0).is_ok());
    assert_eq!(
        OrderingTable::new(limit, 0).unwrap_err(),
        OtError::TooDeep {
            depth: limit,
            max: limit - 1
        }
    );
    assert!(matches!(
        OrderingTable::new(usize::MAX, usize::MAX),
        Err(OtError::TooDeep { .. })
    ));
    let msg = OtError::TooDeep {
        depth: limit,
        max: limit - 1,
    }
    .to_string();
    assert!(msg.contains("2097151") && msg.contains("800000h"), "{msg}");
}

/// A walk of the deepest legal table visits every entry once, far end first, and ends at the
/// terminator in entry 0; a packet at the last entry (byte address 7F_FFF8h) and one at entry
/// 0 both come out, in that order.
#[test]
fn deepest_table_walk_visits_every_entry() {
    let depth = (1usize << 21) - 1;
    let ot = OrderingTable::new(depth, 0).unwrap();
    let stats = ot.walk(|_| {}).unwrap();
    assert_eq!(stats.nodes, depth);
    assert_eq!(stats.packets, 0);

    let depth = (1usize << 20) + 3;
    let mut ot = OrderingTable::new(depth, 64).unwrap();
    ot.insert(depth - 1, &[0xAAAA_AAAA]).unwrap();
    ot.insert(0, &[0xBBBB_BBBB]).unwrap();
    let mut seen = Vec::new();
    let stats = ot.walk(|w| seen.extend_from_slice(w)).unwrap();
    assert_eq!(seen, [0xAAAA_AAAA, 0xBBBB_BBBB]);
    assert_eq!(stats.nodes, depth + 2);
}

/// Huge primitive buffers are cut to what 24-bit links can address instead of allocating
/// words no node could use: 2^21 words in all.
#[test]
fn primitive_buffer_capped_at_link_range() {
    let ot = OrderingTable::new(16, usize::MAX / 2).unwrap();
    assert_eq!(ot.ram().len(), 1 << 21);
}
