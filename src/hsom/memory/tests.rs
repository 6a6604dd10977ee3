use super::*;

#[test]
fn list_is_fifo_newest_first() {
    let mut l = ActivityList::new(3);
    assert!(l.is_empty());
    l.push((1, 0));
    l.push((2, 0));
    assert_eq!(l.to_vec(), vec![(2, 0), (1, 0)]);
    l.push((3, 0));
    assert!(l.is_full());
    l.push((4, 0));
    assert_eq!(l.to_vec(), vec![(4, 0), (3, 0), (2, 0)]);
    assert_eq!(l.get(3), None);
    l.clear();
    assert_eq!(l.len(), 0);
    l.push((9, 9));
    assert_eq!(l.to_vec(), vec![(9, 9)]);
}

#[test]
fn encode_shifts_known_entries_and_masks_the_rest() {
    let mut l = ActivityList::new(4);
    for i in 1..=3u16 {
        l.push((i, 10 + i));
    }
    let mut out = vec![-1.0; 8];
    let mut mask = vec![true; 8];
    l.encode(3, 1, &mut out, &mut mask);
    assert_eq!(mask, [false, false, true, true, true, true, true, true]);
    assert_eq!(&out[2..], &[3.0, 13.0, 2.0, 12.0, 1.0, 11.0]);
}

#[test]
fn levels_decay_linearly_as_in_footnote_1() {
    let mut a = ActivityLevels::new(6, 4);
    for n in 0..5 {
        a.push(n);
    }
    assert_eq!(a.levels(), &[0.0, 0.25, 0.5, 0.75, 1.0, 0.0]);
    assert_eq!(a.active(), 4);
}
