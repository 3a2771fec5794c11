/* A C99 program using tessera as a pipeline would, through tessera_c.h and pkg-config alone
 * (tests/c_api/consumer_test.sh builds it with -std=c99 -Wall -Wextra -Werror -pedantic
 * against an installed tree and compares its file with `tessera compress`'s):
 *
 *   consumer IN.rgba WIDTH HEIGHT OUT.ktx2 fast|normal|high
 *
 * reads WIDTH x HEIGHT raw RGBA8 texels, encodes them with a full mip chain and alpha bleed,
 * writes a Zstandard KTX 2.0 file (size query, then the caller's buffer), reads the file back,
 * decodes level 0 into a padded buffer and prints its PSNR and SSIM against the input.
 * Exit 0 on success, 1 with the library's message otherwise. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tessera/tessera_c.h>

static int progress_calls = 0;
static double last_fraction = -1.0;

static int on_progress(void* user_data, double fraction) {
  (void)user_data;
  if (fraction < last_fraction) {
    fprintf(stderr, "consumer: progress went back from %f to %f\n", last_fraction, fraction);
  }
  last_fraction = fraction;
  ++progress_calls;
  return 0; /* go on */
}

static int fail(tessera_context* context, const char* what, tessera_error error) {
  fprintf(stderr, "consumer: %s: %s: %s\n", what, tessera_error_string(error),
          tessera_context_last_error(context));
  return 1;
}

static unsigned char* read_all(const char* path, size_t expected) {
  FILE* f = fopen(path, "rb");
  unsigned char* bytes = NULL;
  if (f == NULL) return NULL;
  bytes = (unsigned char*)malloc(expected + 1);
  if (bytes != NULL && fread(bytes, 1, expected + 1, f) != expected) {
    free(bytes);
    bytes = NULL;
  }
  fclose(f);
  return bytes;
}

static int run(tessera_context* context, const tessera_image* image, const char* out_path,
               tessera_quality quality) {
  tessera_encode_options options;
  tessera_texture* texture = NULL;
  tessera_texture* back = NULL;
  tessera_texture_info info;
  tessera_metrics metrics;
  tessera_image decoded;
  unsigned char* file = NULL;
  unsigned char* pixels = NULL;
  size_t size = 0, pitch = 0;
  FILE* f = NULL;
  tessera_error e;
  int rc = 1;

  tessera_encode_options_init(&options);
  options.quality = quality;
  options.flags = TESSERA_FLAG_MIPMAPS | TESSERA_FLAG_ALPHA_BLEED;
  e = tessera_encode(context, image, 1, &options, &texture);
  if (e != TESSERA_SUCCESS) return fail(context, "encode", e);

  /* The size first, then the bytes into our own buffer. */
  e = tessera_texture_write_memory(context, texture, TESSERA_CONTAINER_KTX2, 5, NULL, 0, &size);
  if (e != TESSERA_SUCCESS) {
    rc = fail(context, "size of the KTX2 file", e);
    goto done;
  }
  file = (unsigned char*)malloc(size);
  if (file == NULL) goto done;
  e = tessera_texture_write_memory(context, texture, TESSERA_CONTAINER_KTX2, 5, file, size - 1,
                                   &size);
  if (e != TESSERA_ERROR_BUFFER_TOO_SMALL) {
    fprintf(stderr, "consumer: a buffer one byte short gave %s\n", tessera_error_string(e));
    goto done;
  }
  e = tessera_texture_write_memory(context, texture, TESSERA_CONTAINER_KTX2, 5, file, size, &size);
  if (e != TESSERA_SUCCESS) {
    rc = fail(context, "KTX2 file", e);
    goto done;
  }
  f = fopen(out_path, "wb");
  if (f == NULL || fwrite(file, 1, size, f) != size || fclose(f) != 0) {
    fprintf(stderr, "consumer: cannot write %s\n", out_path);
    goto done;
  }

  /* Read it back, decode level 0 into a padded buffer and measure it. */
  e = tessera_texture_read_file(context, out_path, &back);
  if (e != TESSERA_SUCCESS) {
    rc = fail(context, "read back", e);
    goto done;
  }
  info.struct_size = sizeof info;
  e = tessera_texture_get_info(back, &info);
  if (e != TESSERA_SUCCESS) {
    rc = fail(context, "info", e);
    goto done;
  }
  pitch = 4u * info.width + 12u;
  pixels = (unsigned char*)malloc(pitch * info.height);
  if (pixels == NULL) goto done;
  e = tessera_texture_decode(context, back, 0, 0, 0, pixels, pitch, pitch * info.height);
  if (e != TESSERA_SUCCESS) {
    rc = fail(context, "decode", e);
    goto done;
  }
  decoded.pixels = pixels;
  decoded.width = info.width;
  decoded.height = info.height;
  decoded.row_pitch = pitch;
  decoded.has_alpha = info.has_alpha;
  metrics.struct_size = sizeof metrics;
  e = tessera_compare(context, image, &decoded, 1, &metrics);
  if (e != TESSERA_SUCCESS) {
    rc = fail(context, "compare", e);
    goto done;
  }
  printf("%ux%u, %u levels, %lu bytes, PSNR %.2f dB, SSIM %.4f, %d progress calls (last %.3f)\n",
         info.width, info.height, info.levels, (unsigned long)size, metrics.psnr_rgb, metrics.ssim,
         progress_calls, last_fraction);
  rc = progress_calls > 0 && last_fraction == 1.0 ? 0 : 1;

done:
  free(file);
  free(pixels);
  tessera_texture_free(texture);
  tessera_texture_free(back);
  return rc;
}

int main(int argc, char** argv) {
  tessera_context_config config;
  tessera_context* context = NULL;
  tessera_image image;
  tessera_quality quality = TESSERA_QUALITY_NORMAL;
  unsigned char* texels = NULL;
  int rc;
  if (argc != 6) {
    fprintf(stderr, "usage: consumer IN.rgba WIDTH HEIGHT OUT.ktx2 fast|normal|high\n");
    return 2;
  }
  image.width = (uint32_t)strtoul(argv[2], NULL, 10);
  image.height = (uint32_t)strtoul(argv[3], NULL, 10);
  image.row_pitch = 0; /* packed */
  image.has_alpha = 1;
  if (strcmp(argv[5], "fast") == 0) quality = TESSERA_QUALITY_FAST;
  if (strcmp(argv[5], "high") == 0) quality = TESSERA_QUALITY_HIGH;
  texels = read_all(argv[1], (size_t)image.width * image.height * 4u);
  if (texels == NULL) {
    fprintf(stderr, "consumer: %s is not %s x %s RGBA8 texels\n", argv[1], argv[2], argv[3]);
    return 1;
  }
  image.pixels = texels;

  tessera_context_config_init(&config);
  config.threads = 2;
  config.progress = on_progress;
  if (tessera_context_create(&config, &context) != TESSERA_SUCCESS) return 1;
  printf("tessera %s (C API %d)\n", tessera_version(), TESSERA_C_API_VERSION);
  rc = run(context, &image, argv[4], quality);
  tessera_context_free(context);
  free(texels);
  return rc;
}
