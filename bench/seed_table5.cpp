// Retyped from the dissertation (Tables 3 and 5); only the function frame is new. Kept as printed,
// including its style, so the comparison is with the published code.
#include "seed_table5.hpp"

#include <opencv2/core/fast_math.hpp>

unsigned char g_chromaticityTable[256 * 3 * 256];

void seedInitChromaticityTable()
{
    int i, j;
    // at initialization
    for (i = 0; i < 256 * 3; i++) {
        for (j = 0; j < 256; j++) {
            if (i == 0)
                g_chromaticityTable[j] = 0;
            else
                g_chromaticityTable[(i << 8) + j] =
                    (unsigned char)cvRound(255.0f * (float)j / (float)i);
        }
    }
}

void seedChromaticityTable5(SeedIplImage* m_inputImage, SeedIplImage* const m_planes[3],
                            SeedSize m_imageSize)
{
    unsigned char* iPtr = (unsigned char*)m_inputImage->imageData;
    unsigned char* p0 = (unsigned char*)m_planes[0]->imageData;
    unsigned char* p1 = (unsigned char*)m_planes[1]->imageData;
    unsigned char* p2 = (unsigned char*)m_planes[2]->imageData;
    unsigned char* tablePtr;
    int i;
    int sum;
    for (i = (m_imageSize.width * m_imageSize.height) / 4; i > 0;
         i--, iPtr += 12, p0 += 4, p1 += 4, p2 += 4) {
        sum = iPtr[0] + iPtr[1] + iPtr[2];
        tablePtr = g_chromaticityTable + (sum << 8);
        p0[0] = tablePtr[iPtr[0]];
        p1[0] = tablePtr[iPtr[1]];
        p2[0] = tablePtr[iPtr[2]];
        sum = iPtr[3] + iPtr[4] + iPtr[5];
        tablePtr = g_chromaticityTable + (sum << 8);
        p0[1] = tablePtr[iPtr[3]];
        p1[1] = tablePtr[iPtr[4]];
        p2[1] = tablePtr[iPtr[5]];
        sum = iPtr[6] + iPtr[7] + iPtr[8];
        tablePtr = g_chromaticityTable + (sum << 8);
        p0[2] = tablePtr[iPtr[6]];
        p1[2] = tablePtr[iPtr[7]];
        p2[2] = tablePtr[iPtr[8]];
        sum = iPtr[9] + iPtr[10] + iPtr[11];
        tablePtr = g_chromaticityTable + (sum << 8);
        p0[3] = tablePtr[iPtr[9]];
        p1[3] = tablePtr[iPtr[10]];
        p2[3] = tablePtr[iPtr[11]];
    }
}
