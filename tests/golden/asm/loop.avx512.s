; inputs finite with |x| <= 65536 (other batches run the general code)
; 4 points per iteration (xmm registers)
L0:
     0    push rbx
     1    push rbp
     2    push r12
     4    push r13
     6    push r14
     8    push r15
     a    sub rsp, 680
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
    31    pcmpeqd xmm0, xmm0
    35    movaps [rsp+224], xmm0
    3d    xorps xmm1, xmm1
    40    movaps [rsp+240], xmm1
    48    movaps [rsp+256], xmm1
    50    movaps [rsp+272], xmm1
    58    movaps [rsp+112], xmm1
    5d    movaps [rsp+128], xmm1
    65    movaps [rsp+144], xmm1
    6d    movaps [rsp+208], xmm1
L4:
    75    movaps xmm0, [rsp+224]
    7d    movmskps rax, xmm0
    80    test rax, rax
    83    je L5
    89    movaps [rsp+64], xmm0
    8e    xorps xmm1, xmm1
    91    movaps [rsp+224], xmm1
    99    mov rax, [rbx]
    9c    movups xmm2, [rax+r13*1]
    a1    movaps [rsp+288], xmm2
    a9    movaps xmm0, [rsp+64]
    ae    movaps [rsp+80], xmm0
    b3    movaps xmm1, [rip+L9]
    ba    movaps [rsp+384], xmm1
    c2    movaps xmm1, [rip+L9]
    c9    movaps [rsp+400], xmm1
    d1    movaps xmm0, [rsp+80]
    d6    movaps xmm1, [rsp+320]
    de    blendvps xmm1, [rsp+384]
    e8    movaps [rsp+320], xmm1
    f0    movaps xmm0, [rsp+80]
    f5    movaps xmm1, [rsp+336]
    fd    blendvps xmm1, [rsp+400]
   107    movaps [rsp+336], xmm1
   10f    movaps xmm1, [rsp+240]
   117    orps xmm1, [rsp+80]
   11c    movaps [rsp+240], xmm1
L5:
   124    movaps xmm0, [rsp+240]
   12c    movmskps rax, xmm0
   12f    test rax, rax
   132    je L6
   138    movaps [rsp+64], xmm0
   13d    xorps xmm1, xmm1
   140    movaps [rsp+240], xmm1
   148    movaps xmm2, [rsp+320]
   150    cmpltps xmm2, [rip+L10]
   158    andps xmm2, [rip+L11]
   15f    movaps xmm0, xmm2
   162    cmpneqps xmm0, [rip+L9]
   16a    movaps xmm1, [rsp+64]
   16f    andps xmm1, xmm0
   172    movaps [rsp+80], xmm1
   177    andnps xmm0, [rsp+64]
   17c    movaps [rsp+96], xmm0
   181    movaps xmm1, [rsp+256]
   189    orps xmm1, [rsp+80]
   18e    movaps [rsp+256], xmm1
   196    movaps xmm1, [rsp+272]
   19e    orps xmm1, [rsp+96]
   1a3    movaps [rsp+272], xmm1
L6:
   1ab    movaps xmm0, [rsp+256]
   1b3    movmskps rax, xmm0
   1b6    test rax, rax
   1b9    je L7
   1bf    movaps [rsp+64], xmm0
   1c4    xorps xmm1, xmm1
   1c7    movaps [rsp+256], xmm1
   1cf    movaps xmm0, [rsp+112]
   1d4    psubd xmm0, [rsp+64]
   1da    movaps [rsp+112], xmm0
   1df    pcmpgtd xmm0, [rip+L12]
   1e7    movmskps rax, xmm0
   1ea    test rax, rax
   1ed    jne L13
   1f3    mov rax, 0xADDRESS
   1fd    mov rax, [rax]
   200    cmp8 [rax], 0
   203    jne L14
   209    movaps xmm2, [rsp+336]
   211    addps xmm2, [rsp+288]
   219    movaps xmm0, [rsp+64]
   21e    movaps xmm1, [rsp+352]
   226    blendvps xmm1, xmm2
   22b    movaps [rsp+352], xmm1
   233    movaps xmm3, [rsp+320]
   23b    addps xmm3, [rip+L11]
   242    movaps xmm0, [rsp+64]
   247    movaps xmm1, [rsp+368]
   24f    blendvps xmm1, xmm3
   254    movaps [rsp+368], xmm1
   25c    movaps xmm0, [rsp+64]
   261    movaps [rsp+80], xmm0
   266    movaps [rsp+384], xmm3
   26e    movaps [rsp+400], xmm2
   276    movaps xmm0, [rsp+80]
   27b    movaps xmm1, [rsp+320]
   283    blendvps xmm1, [rsp+384]
   28d    movaps [rsp+320], xmm1
   295    movaps xmm0, [rsp+80]
   29a    movaps xmm1, [rsp+336]
   2a2    blendvps xmm1, [rsp+400]
   2ac    movaps [rsp+336], xmm1
   2b4    movaps xmm1, [rsp+240]
   2bc    orps xmm1, [rsp+80]
   2c1    movaps [rsp+240], xmm1
   2c9    movaps xmm0, [rsp+80]
   2ce    movmskps rax, xmm0
   2d1    test rax, rax
   2d4    jne L5
L7:
   2da    movaps xmm0, [rsp+272]
   2e2    movmskps rax, xmm0
   2e5    test rax, rax
   2e8    je L8
   2ee    movaps [rsp+64], xmm0
   2f3    xorps xmm1, xmm1
   2f6    movaps [rsp+272], xmm1
   2fe    movaps xmm0, [rsp+64]
   303    movaps xmm1, [rsp+208]
   30b    blendvps xmm1, [rsp+336]
   315    movaps [rsp+208], xmm1
L8:
   31d    xorps xmm0, xmm0
   320    orps xmm0, [rsp+224]
   328    orps xmm0, [rsp+240]
   330    orps xmm0, [rsp+256]
   338    orps xmm0, [rsp+272]
   340    movmskps rax, xmm0
   343    test rax, rax
   346    jne L4
   34c    movaps xmm0, [rsp+208]
   354    mov rax, [r12]
   358    movups [rax+r13*1], xmm0
   35d    add r13, 16
   361    jmp L2
L3:
   366    mov rax, 0x0
L1:
   36b    add rsp, 680
   372    pop r15
   374    pop r14
   376    pop r13
   378    pop r12
   37a    pop rbp
   37b    pop rbx
   37c    ret
L13:
   37d    mov rax, 0x100000300000004
   387    jmp L1
L14:
   38c    mov rax, 0x500000300000004
   396    jmp L1
L9:
   3a0    .float 0, 0, 0, 0
L10:
   3b0    .float 3, 3, 3, 3
L11:
   3c0    .float 1, 1, 1, 1
L12:
   3d0    .float 1.40129846e-38, 1.40129846e-38, 1.40129846e-38, 1.40129846e-38
