; 4 points per iteration (xmm registers)
L0:
     0    push rbx
     1    push rbp
     2    push r12
     4    push r13
     6    push r14
     8    push r15
     a    sub rsp, 504
    11    mov rbx, rdi
    14    mov r12, rsi
    17    mov r15, r8
    1a    lea r13, [rdx+rdx*2]
    1e    add r13, rdx
    21    lea r14, [rcx+rcx*2]
    25    add r14, rcx
L2:
    28    cmp r13, r14
    2b    jae L3
L4:
    31    mov rax, [rbx]
    34    movups xmm2, [rax+r13*1]
    39    movaps xmm1, xmm2
    3c    movaps [rsp], xmm1
    40    movaps xmm0, xmm1
    43    andps xmm0, [rip+L6]
    4a    cmpleps xmm0, [rip+L7]
    52    movmskps rax, xmm0
    55    cmp rax, 15
    59    jne L8
    5f    cvtps2pd xmm3, xmm1
    62    movhlps xmm1, xmm1
    65    cvtps2pd xmm4, xmm1
    68    movaps xmm5, xmm3
    6b    mulpd xmm5, [rip+L10]
    73    addpd xmm5, [rip+L11]
    7b    subpd xmm5, [rip+L11]
    83    movaps xmm0, xmm5
    86    mulpd xmm0, [rip+L12]
    8e    subpd xmm3, xmm0
    92    movaps xmm0, xmm5
    95    mulpd xmm0, [rip+L13]
    9d    subpd xmm3, xmm0
    a1    cvttpd2dq xmm5, xmm5
    a5    cvtpd2ps xmm3, xmm3
    a9    movaps xmm6, xmm4
    ac    mulpd xmm6, [rip+L10]
    b4    addpd xmm6, [rip+L11]
    bc    subpd xmm6, [rip+L11]
    c4    movaps xmm0, xmm6
    c7    mulpd xmm0, [rip+L12]
    cf    subpd xmm4, xmm0
    d3    movaps xmm0, xmm6
    d6    mulpd xmm0, [rip+L13]
    de    subpd xmm4, xmm0
    e2    cvttpd2dq xmm6, xmm6
    e6    cvtpd2ps xmm4, xmm4
    ea    movlhps xmm3, xmm4
    ed    punpcklqdq xmm5, xmm6
    f1    movaps xmm4, xmm3
    f4    mulps xmm4, xmm3
    f7    movaps xmm6, [rip+L14]
    fe    mulps xmm6, xmm4
   101    addps xmm6, [rip+L15]
   108    mulps xmm6, xmm4
   10b    subps xmm6, [rip+L16]
   112    mulps xmm6, xmm4
   115    mulps xmm6, xmm3
   118    addps xmm6, xmm3
   11b    movaps xmm1, xmm3
   11e    andps xmm1, [rip+L17]
   125    orps xmm6, xmm1
   128    movaps xmm7, [rip+L18]
   12f    mulps xmm7, xmm4
   132    subps xmm7, [rip+L19]
   139    mulps xmm7, xmm4
   13c    addps xmm7, [rip+L20]
   143    mulps xmm7, xmm4
   146    mulps xmm7, xmm4
   149    movaps xmm1, [rip+L21]
   150    mulps xmm1, xmm4
   153    subps xmm7, xmm1
   156    addps xmm7, [rip+L22]
   15d    movaps xmm1, xmm5
   160    movaps xmm0, xmm1
   163    pand xmm0, [rip+L23]
   16b    pcmpeqd xmm0, [rip+L23]
   173    movaps xmm3, xmm6
   176    blendvps xmm3, xmm7
   17b    pand xmm1, [rip+L24]
   183    pslld xmm1, 30
   188    xorps xmm3, xmm1
   18b    movaps xmm1, xmm5
   18e    paddd xmm1, [rip+L23]
   196    movaps xmm0, xmm1
   199    pand xmm0, [rip+L23]
   1a1    pcmpeqd xmm0, [rip+L23]
   1a9    movaps xmm4, xmm6
   1ac    blendvps xmm4, xmm7
   1b1    pand xmm1, [rip+L24]
   1b9    pslld xmm1, 30
   1be    xorps xmm4, xmm1
L9:
   1c1    mulps xmm3, xmm4
   1c4    mov rax, [r12]
   1c8    movups [rax+r13*1], xmm3
L5:
   1cd    add r13, 16
   1d1    jmp L2
L3:
   1d6    mov rax, 0x0
L1:
   1db    add rsp, 504
   1e2    pop r15
   1e4    pop r14
   1e6    pop r13
   1e8    pop r12
   1ea    pop rbp
   1eb    pop rbx
   1ec    ret
L8:
   1ed    movaps [rsp+272], xmm2
   1f5    movaps [rsp+288], xmm3
   1fd    movaps [rsp+304], xmm4
   205    movaps [rsp+320], xmm5
   20d    movaps [rsp+336], xmm6
   215    movaps [rsp+352], xmm7
   21d    movaps [rsp+368], xmm8
   226    movaps [rsp+384], xmm9
   22f    movaps [rsp+400], xmm10
   238    movaps [rsp+416], xmm11
   241    movaps [rsp+432], xmm12
   24a    movaps [rsp+448], xmm13
   253    movaps [rsp+464], xmm14
   25c    movaps [rsp+480], xmm15
   265    lea rdi, [rsp]
   269    lea rsi, [rsp+48]
   26e    mov rdx, 0x4
   273    mov rax, 0xADDRESS
   27d    call rax
   27f    movaps xmm0, [rsp+48]
   284    movaps [rsp+32], xmm0
   289    lea rdi, [rsp]
   28d    lea rsi, [rsp+48]
   292    mov rdx, 0x4
   297    mov rax, 0xADDRESS
   2a1    call rax
   2a3    movaps xmm2, [rsp+272]
   2ab    movaps xmm3, [rsp+288]
   2b3    movaps xmm4, [rsp+304]
   2bb    movaps xmm5, [rsp+320]
   2c3    movaps xmm6, [rsp+336]
   2cb    movaps xmm7, [rsp+352]
   2d3    movaps xmm8, [rsp+368]
   2dc    movaps xmm9, [rsp+384]
   2e5    movaps xmm10, [rsp+400]
   2ee    movaps xmm11, [rsp+416]
   2f7    movaps xmm12, [rsp+432]
   300    movaps xmm13, [rsp+448]
   309    movaps xmm14, [rsp+464]
   312    movaps xmm15, [rsp+480]
   31b    movaps xmm3, [rsp+32]
   320    movaps xmm4, [rsp+48]
   325    jmp L9
L6:
   330    .float nan, nan, nan, nan
L7:
   340    .float 800000, 800000, 800000, 800000
L10:
   350    .float 7.80611135e+27, 1.78415489, 7.80611135e+27, 1.78415489
L11:
   360    .float 0, 184, 0, 184
L12:
   370    .float 3.29853488e+12, 1.9463495, 3.29853488e+12, 1.9463495
L13:
   380    .float 4.68158308e-23, 0.101906545, 4.68158308e-23, 0.101906545
L14:
   390    .float -0.000195152956, -0.000195152956, -0.000195152956, -0.000195152956
L15:
   3a0    .float 0.00833216123, 0.00833216123, 0.00833216123, 0.00833216123
L16:
   3b0    .float 0.166666552, 0.166666552, 0.166666552, 0.166666552
L17:
   3c0    .float -0, -0, -0, -0
L18:
   3d0    .float 2.44331568e-05, 2.44331568e-05, 2.44331568e-05, 2.44331568e-05
L19:
   3e0    .float 0.00138873165, 0.00138873165, 0.00138873165, 0.00138873165
L20:
   3f0    .float 0.0416666456, 0.0416666456, 0.0416666456, 0.0416666456
L21:
   400    .float 0.5, 0.5, 0.5, 0.5
L22:
   410    .float 1, 1, 1, 1
L23:
   420    .float 1.40129846e-45, 1.40129846e-45, 1.40129846e-45, 1.40129846e-45
L24:
   430    .float 2.80259693e-45, 2.80259693e-45, 2.80259693e-45, 2.80259693e-45
