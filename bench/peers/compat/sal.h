// Stand-in for Microsoft's sal.h (source-code annotation language) so that DirectXMath and its
// SHMath build with g++ and clang++ on Linux: every annotation DirectXMath uses expands to
// nothing. (Debian's directx-headers-dev ships no sal.h.)
#pragma once
#define _In_
#define _In_opt_
#define _In_reads_(s)
#define _In_reads_opt_(s)
#define _In_reads_bytes_(s)
#define _In_reads_bytes_opt_(s)
#define _Out_
#define _Out_opt_
#define _Out_writes_(s)
#define _Out_writes_opt_(s)
#define _Out_writes_bytes_(s)
#define _Out_writes_bytes_opt_(s)
#define _Out_writes_all_(s)
#define _Inout_
#define _Inout_opt_
#define _Inout_updates_(s)
#define _Inout_updates_bytes_(s)
#define _Use_decl_annotations_
#define _Analysis_assume_(e)
#define _Success_(e)
#define _Check_return_
#define _Ret_maybenull_
#define _Ret_notnull_
#define _Printf_format_string_
