//! A universal ("fat") Mach-O file from thin ones, as Apple's `lipo -create` writes it:
//! FMI 2.0 has one macOS folder, `darwin64`, which fmpy loads on Intel and Apple Silicon
//! alike, so its library holds both architectures.
//!
//! ```text
//! fat_header   magic 0xcafebabe, nfat_arch             (big-endian u32 each)
//! fat_arch[n]  cputype, cpusubtype, offset, size, align (big-endian u32 each; align = log2)
//! ...          each thin file, unchanged, at its offset (a multiple of 2^align)
//! ```
//!
//! The thin files are copied byte for byte, so the ad-hoc code signature of the arm64 one
//! (which covers that slice alone) stays valid.

type BoxError = Box<dyn std::error::Error>;

const FAT_MAGIC: u32 = 0xcafe_babe;
const MH_MAGIC_64: u32 = 0xfeed_facf;
/// 2^14 = 16 KiB, the page size of arm64 macOS (lipo's alignment for arm64 slices; also
/// a multiple of x86_64's 4 KiB pages).
const ALIGN_LOG2: u32 = 14;

/// The universal file holding every thin 64-bit Mach-O file of `slices`, in that order.
pub fn universal(slices: &[&[u8]]) -> Result<Vec<u8>, BoxError> {
    let align = 1usize << ALIGN_LOG2;
    let mut header = Vec::new();
    header.extend(FAT_MAGIC.to_be_bytes());
    header.extend(u32::try_from(slices.len())?.to_be_bytes());
    let mut offset = align; // the headers fit in the first aligned block
    let mut body = Vec::new();
    for slice in slices {
        let word = |at: usize| -> Result<u32, BoxError> {
            let bytes = slice.get(at..at + 4).ok_or("thin Mach-O file shorter than its header")?;
            Ok(u32::from_le_bytes(bytes.try_into()?))
        };
        if word(0)? != MH_MAGIC_64 {
            return Err("not a little-endian 64-bit Mach-O file".into());
        }
        for field in
            [word(4)?, word(8)?, u32::try_from(offset)?, u32::try_from(slice.len())?, ALIGN_LOG2]
        {
            header.extend(field.to_be_bytes());
        }
        body.resize(offset - align, 0);
        body.extend_from_slice(slice);
        offset = (align + body.len()).next_multiple_of(align);
    }
    if header.len() > align {
        return Err("too many slices for one header block".into());
    }
    header.resize(align, 0);
    header.extend(body);
    Ok(header)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn thin(cputype: u32, len: usize) -> Vec<u8> {
        let mut bytes = vec![0xab; len];
        bytes[..4].copy_from_slice(&MH_MAGIC_64.to_le_bytes());
        bytes[4..8].copy_from_slice(&cputype.to_le_bytes());
        bytes[8..12].copy_from_slice(&3u32.to_le_bytes());
        bytes
    }

    #[test]
    fn slices_at_aligned_offsets_unchanged() {
        let (x86, arm) = (thin(0x0100_0007, 20_000), thin(0x0100_000c, 5_000));
        let fat = universal(&[&x86, &arm]).unwrap();
        let be = |at: usize| u32::from_be_bytes(fat[at..at + 4].try_into().unwrap()) as usize;
        assert_eq!((be(0) as u32, be(4)), (FAT_MAGIC, 2));
        for (k, slice) in [&x86, &arm].into_iter().enumerate() {
            let entry = 8 + 20 * k;
            let (cputype, offset, size) = (be(entry), be(entry + 8), be(entry + 12));
            assert_eq!(cputype as u32, u32::from_le_bytes(slice[4..8].try_into().unwrap()));
            assert_eq!(offset % (1 << ALIGN_LOG2), 0);
            assert_eq!(&fat[offset..offset + size], slice.as_slice());
        }
        assert_eq!(be(8 + 8), 1 << 14);
        assert_eq!(be(28 + 8), 3 << 14); // 20,000 bytes take two blocks after the first
        assert!(universal(&[&[0u8; 16][..]]).is_err());
    }
}
