; 8 points per iteration (ymm registers)
L0:
     0    push rbx
     1    push rbp
     2    push r12
     4    push r13
     6    push r14
     8    push r15
     a    mov rbp, rsp
     d    sub rsp, 776
    14    and rsp, -32
    18    mov rbx, rdi
    1b    mov r12, rsi
    1e    mov r15, r8
    21    lea r13, [rdx+rdx*2]
    25    add r13, rdx
    28    lea r14, [rcx+rcx*2]
    2c    add r14, rcx
L2:
    2f    cmp r13, r14
    32    jae L3
L4:
    38    mov rax, [rbx]
    3b    vmovups ymm2, [rax+r13*1]
    41    vmovaps ymm1, ymm2
    45    vmovaps [rsp], ymm1
    4a    vmovaps ymm0, ymm1
    4e    vandps ymm0, ymm0, [rip+L6]
    56    vcmpleps ymm0, ymm0, [rip+L7]
    5f    vmovmskps rax, ymm0
    63    cmp rax, 255
    6a    jne L8
    70    vcvtps2pd ymm3, xmm1
    74    vextractf128 xmm1, ymm1, 1
    7a    vcvtps2pd ymm4, xmm1
    7e    vmovaps ymm5, ymm3
    82    vmulpd ymm5, ymm5, [rip+L10]
    8a    vaddpd ymm5, ymm5, [rip+L11]
    92    vsubpd ymm5, ymm5, [rip+L11]
    9a    vmovaps ymm0, ymm5
    9e    vmulpd ymm0, ymm0, [rip+L12]
    a6    vsubpd ymm3, ymm3, ymm0
    aa    vmovaps ymm0, ymm5
    ae    vmulpd ymm0, ymm0, [rip+L13]
    b6    vsubpd ymm3, ymm3, ymm0
    ba    vcvttpd2dq xmm5, ymm5
    be    vcvtpd2ps xmm3, ymm3
    c2    vmovaps ymm6, ymm4
    c6    vmulpd ymm6, ymm6, [rip+L10]
    ce    vaddpd ymm6, ymm6, [rip+L11]
    d6    vsubpd ymm6, ymm6, [rip+L11]
    de    vmovaps ymm0, ymm6
    e2    vmulpd ymm0, ymm0, [rip+L12]
    ea    vsubpd ymm4, ymm4, ymm0
    ee    vmovaps ymm0, ymm6
    f2    vmulpd ymm0, ymm0, [rip+L13]
    fa    vsubpd ymm4, ymm4, ymm0
    fe    vcvttpd2dq xmm6, ymm6
   102    vcvtpd2ps xmm4, ymm4
   106    vinsertf128 ymm3, ymm3, xmm4, 1
   10c    vinsertf128 ymm5, ymm5, xmm6, 1
   112    vmovaps ymm4, ymm3
   116    vmulps ymm4, ymm4, ymm3
   11a    vmovaps ymm6, [rip+L14]
   122    vmulps ymm6, ymm6, ymm4
   126    vaddps ymm6, ymm6, [rip+L15]
   12e    vmulps ymm6, ymm6, ymm4
   132    vsubps ymm6, ymm6, [rip+L16]
   13a    vmulps ymm6, ymm6, ymm4
   13e    vmulps ymm6, ymm6, ymm3
   142    vaddps ymm6, ymm6, ymm3
   146    vmovaps ymm1, ymm3
   14a    vandps ymm1, ymm1, [rip+L17]
   152    vorps ymm6, ymm6, ymm1
   156    vmovaps ymm7, [rip+L18]
   15e    vmulps ymm7, ymm7, ymm4
   162    vsubps ymm7, ymm7, [rip+L19]
   16a    vmulps ymm7, ymm7, ymm4
   16e    vaddps ymm7, ymm7, [rip+L20]
   176    vmulps ymm7, ymm7, ymm4
   17a    vmulps ymm7, ymm7, ymm4
   17e    vmovaps ymm1, [rip+L21]
   186    vmulps ymm1, ymm1, ymm4
   18a    vsubps ymm7, ymm7, ymm1
   18e    vaddps ymm7, ymm7, [rip+L22]
   196    vmovaps ymm1, ymm5
   19a    vmovaps ymm0, ymm1
   19e    vpand ymm0, ymm0, [rip+L23]
   1a6    vpcmpeqd ymm0, ymm0, [rip+L23]
   1ae    vmovaps ymm3, ymm6
   1b2    vblendvps ymm3, ymm3, ymm7, ymm0
   1b8    vpand ymm1, ymm1, [rip+L24]
   1c0    vpslld ymm1, 30
   1c5    vxorps ymm3, ymm3, ymm1
   1c9    vmovaps ymm1, ymm5
   1cd    vpaddd ymm1, ymm1, [rip+L23]
   1d5    vmovaps ymm0, ymm1
   1d9    vpand ymm0, ymm0, [rip+L23]
   1e1    vpcmpeqd ymm0, ymm0, [rip+L23]
   1e9    vmovaps ymm4, ymm6
   1ed    vblendvps ymm4, ymm4, ymm7, ymm0
   1f3    vpand ymm1, ymm1, [rip+L24]
   1fb    vpslld ymm1, 30
   200    vxorps ymm4, ymm4, ymm1
L9:
   204    vmulps ymm3, ymm3, ymm4
   208    mov rax, [r12]
   20c    vmovups [rax+r13*1], ymm3
L5:
   212    add r13, 32
   216    jmp L2
L3:
   21b    mov rax, 0x0
L1:
   220    mov rsp, rbp
   223    pop r15
   225    pop r14
   227    pop r13
   229    pop r12
   22b    pop rbp
   22c    pop rbx
   22d    vzeroupper
   230    ret
L8:
   231    vmovaps [rsp+320], ymm2
   23a    vmovaps [rsp+352], ymm3
   243    vmovaps [rsp+384], ymm4
   24c    vmovaps [rsp+416], ymm5
   255    vmovaps [rsp+448], ymm6
   25e    vmovaps [rsp+480], ymm7
   267    vmovaps [rsp+512], ymm8
   270    vmovaps [rsp+544], ymm9
   279    vmovaps [rsp+576], ymm10
   282    vmovaps [rsp+608], ymm11
   28b    vmovaps [rsp+640], ymm12
   294    vmovaps [rsp+672], ymm13
   29d    vmovaps [rsp+704], ymm14
   2a6    vmovaps [rsp+736], ymm15
   2af    lea rdi, [rsp]
   2b3    lea rsi, [rsp+96]
   2b8    mov rdx, 0x8
   2bd    mov rax, 0xADDRESS
   2c7    vzeroupper
   2ca    call rax
   2cc    vmovaps ymm0, [rsp+96]
   2d2    vmovaps [rsp+64], ymm0
   2d8    lea rdi, [rsp]
   2dc    lea rsi, [rsp+96]
   2e1    mov rdx, 0x8
   2e6    mov rax, 0xADDRESS
   2f0    vzeroupper
   2f3    call rax
   2f5    vmovaps ymm2, [rsp+320]
   2fe    vmovaps ymm3, [rsp+352]
   307    vmovaps ymm4, [rsp+384]
   310    vmovaps ymm5, [rsp+416]
   319    vmovaps ymm6, [rsp+448]
   322    vmovaps ymm7, [rsp+480]
   32b    vmovaps ymm8, [rsp+512]
   334    vmovaps ymm9, [rsp+544]
   33d    vmovaps ymm10, [rsp+576]
   346    vmovaps ymm11, [rsp+608]
   34f    vmovaps ymm12, [rsp+640]
   358    vmovaps ymm13, [rsp+672]
   361    vmovaps ymm14, [rsp+704]
   36a    vmovaps ymm15, [rsp+736]
   373    vmovaps ymm3, [rsp+64]
   379    vmovaps ymm4, [rsp+96]
   37f    jmp L9
L6:
   3a0    .float nan, nan, nan, nan, nan, nan, nan, nan
L7:
   3c0    .float 800000, 800000, 800000, 800000, 800000, 800000, 800000, 800000
L10:
   3e0    .float 7.80611135e+27, 1.78415489, 7.80611135e+27, 1.78415489, 7.80611135e+27, 1.78415489, 7.80611135e+27, 1.78415489
L11:
   400    .float 0, 184, 0, 184, 0, 184, 0, 184
L12:
   420    .float 3.29853488e+12, 1.9463495, 3.29853488e+12, 1.9463495, 3.29853488e+12, 1.9463495, 3.29853488e+12, 1.9463495
L13:
   440    .float 4.68158308e-23, 0.101906545, 4.68158308e-23, 0.101906545, 4.68158308e-23, 0.101906545, 4.68158308e-23, 0.101906545
L14:
   460    .float -0.000195152956, -0.000195152956, -0.000195152956, -0.000195152956, -0.000195152956, -0.000195152956, -0.000195152956, -0.000195152956
L15:
   480    .float 0.00833216123, 0.00833216123, 0.00833216123, 0.00833216123, 0.00833216123, 0.00833216123, 0.00833216123, 0.00833216123
L16:
   4a0    .float 0.166666552, 0.166666552, 0.166666552, 0.166666552, 0.166666552, 0.166666552, 0.166666552, 0.166666552
L17:
   4c0    .float -0, -0, -0, -0, -0, -0, -0, -0
L18:
   4e0    .float 2.44331568e-05, 2.44331568e-05, 2.44331568e-05, 2.44331568e-05, 2.44331568e-05, 2.44331568e-05, 2.44331568e-05, 2.44331568e-05
L19:
   500    .float 0.00138873165, 0.00138873165, 0.00138873165, 0.00138873165, 0.00138873165, 0.00138873165, 0.00138873165, 0.00138873165
L20:
   520    .float 0.0416666456, 0.0416666456, 0.0416666456, 0.0416666456, 0.0416666456, 0.0416666456, 0.0416666456, 0.0416666456
L21:
   540    .float 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5
L22:
   560    .float 1, 1, 1, 1, 1, 1, 1, 1
L23:
   580    .float 1.40129846e-45, 1.40129846e-45, 1.40129846e-45, 1.40129846e-45, 1.40129846e-45, 1.40129846e-45, 1.40129846e-45, 1.40129846e-45
L24:
   5a0    .float 2.80259693e-45, 2.80259693e-45, 2.80259693e-45, 2.80259693e-45, 2.80259693e-45, 2.80259693e-45, 2.80259693e-45, 2.80259693e-45
