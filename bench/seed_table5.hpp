#pragma once
// The dissertation's final chromaticity code (Table 5, 4.3), retyped as printed and compiled today
// with -O3 (bench/CMakeLists.txt). Its table is Table 3's: 768 rows of 256, filled with OpenCV's
// cvRound of a float quotient (halves to even, so it differs from the exact rule by 1 at ties).

/// Just what the code reads of OpenCV 1.x's IplImage.
struct SeedIplImage {
    char* imageData;
};
struct SeedSize {
    int width;
    int height;
};

/// The global table of Table 5 ("the address can be resolved by the compiler").
extern unsigned char g_chromaticityTable[256 * 3 * 256];

/// Table 3's initialisation of the table.
void seedInitChromaticityTable();

/// Table 5. m_inputImage is packed 3-byte pixels; m_planes[i] receives the chromaticity of byte i
/// of each pixel. The pixel count must be a multiple of 4 (as in the original).
void seedChromaticityTable5(SeedIplImage* m_inputImage, SeedIplImage* const m_planes[3],
                            SeedSize m_imageSize);
